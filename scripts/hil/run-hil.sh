#!/usr/bin/env bash
# run-hil.sh BUILD_DIR: the end-to-end test on emulated hardware. Builds (or reuses) the
# out-of-tree vimc/vkms/gpio-sim modules and the initramfs under BUILD_DIR/hil, boots the
# installed Debian kernel in qemu (TCG) with the host's root shared read-only, runs
# guest-test.sh in it, talks to the guest's second serial port (ttyS1) through a pty, and checks
# that every expected check printed "HIL PASS". Results: BUILD_DIR/hil/results.
# Exit 0 = pass, 1 = fail, 77 = skipped (prints "HIL SKIP: why").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"

[ $# -ge 1 ] || { echo "usage: $0 BUILD_DIR" >&2; exit 2; }
build=$(cd "$1" && pwd)
# The machine's limits, in seconds of an idle reference host: the guest measures how much slower
# this host runs it (calibrate in guest-test.sh, "HIL CALIBRATION ... scale_pct=N", at most
# HIL_SCALE_MAX_PCT) and the whole run's limit, HIL_TIMEOUT, is stretched by the same factor
# once that line is in; before it, the boot and the calibration get boot_limit_s.
# HIL_CALIBRATION_REF_MS is set below what an idle 2-core machine of this kind took on 2026-12-01
# (20.8 s), so even an idle host's deadlines are stretched a little (x1.4); one loaded by a
# parallel build measured 46 s (capped at x4). timeout_max_s is the hard stop whatever the
# calibration says (ctest's TIMEOUT in hil.cmake is above it).
timeout_s=${HIL_TIMEOUT:-400}
calibration_ref_ms=${HIL_CALIBRATION_REF_MS:-15000}
scale_max_pct=${HIL_SCALE_MAX_PCT:-400}
boot_limit_s=${HIL_BOOT_LIMIT_S:-300}
timeout_max_s=$((timeout_s * scale_max_pct / 100 + boot_limit_s))

# The checks the guest runs, in order; each must print "HIL PASS name" (HIL_CHECKS="a b": only
# those). Without packaging: the devices one by one (cam, gpiomon, a shell on ttyS1) and the
# mirror headless. With packaging (cmake/packaging.cmake) the .deb is built and installed in the
# guest, whose postinst starts the unit on the real devices (a drop-in: libcamera:0 on vimc, drm
# on vkms, the buttons on the gpio-sim lines 0 and 1, the console on ttyS1); then the service is
# checked through its console and the faults are tried (package_checks). The host checks the
# snapshot's pixels afterwards (snapshot_image). HIL_SERVICE_TYPE=simple checks the unit with a
# firmware that does not send READY/WATCHDOG yet.
device_checks="camera_listed camera_capture display_connected gpio_sim gpio_edges serial_port"
checks=${HIL_CHECKS:-"modules $device_checks mirror_headless"}
# gpio_sim before the package: the service's drop-in names the chip. camera_listed before it too:
# once the service has configured vimc's pipeline, cam cannot even list it (links busy).
# camera_replug early: the fault runs must start after it (a second process opening the card
# while the service is away would become DRM master), and their ~45-75 s start-up then overlaps
# the button, snapshot and flood checks on the restarted service.
package_checks="modules gpio_sim display_connected camera_listed package_installed
    console_selftest service_ready camera_replug fault_run_start button_press snapshot_drm
    bug_report serial_flood display_bad_mode display_fault gpio_absent serial_absent"
# HIL_SCENARIO=hotplug: the appliance booted with neither camera nor panel (only the V4L2, media
# and DRM cores loaded, as a board's kernel has them), `auto` for both: READY on the calm screen,
# then vimc and vkms loaded and the same process switches to them. HIL_SOAK_MINUTES=N adds N
# cycles of the camera unplugged and plugged in again, with the service's memory after each.
hotplug_checks="core_modules package_installed_bare ready_without_devices devices_plugged_in"
soak_minutes=${HIL_SOAK_MINUTES:-0}
timeout_s=$((timeout_s + soak_minutes * 150))
timeout_max_s=$((timeout_s * scale_max_pct / 100 + boot_limit_s))
# The AddressSanitizer build's device tests run in the machine too when that build exists
# (scripts/dev test builds it before the tests; HIL_ASAN_BIN overrides where to look).
source_dir=$(cd "$here/../.." && pwd)
asan_bin=${HIL_ASAN_BIN:-$source_dir/build-asan/bin}
if [ -x "$asan_bin/devices_live_test" ]; then
    package_checks=${package_checks/display_connected /display_connected asan_devices }
else
    hil_say "no AddressSanitizer build ($asan_bin/devices_live_test): check asan_devices not run"
fi
# The mode of vkms the service is given (the snapshot's size).
display_size="640 480"

[ "$(uname -m)" = x86_64 ] || hil_skip "the emulated machine is x86-64 (host is $(uname -m))"
hil_find_kernel
hil_require_tools qemu-system-x86_64 busybox cpio gzip depmod modprobe udevadm cam gpioget gpiomon make gcc
[ -x /lib/systemd/systemd-udevd ] || hil_skip "systemd-udevd missing (apt-get install udev)"
[ -f /usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so ] ||
    hil_skip "libcamera's vimc IPA missing (apt-get install libcamera-ipa)"
[ -x "$build/bin/mirror" ] || { hil_say "no $build/bin/mirror: build first"; exit 1; }

work=$build/hil
modules=$("$here/build-modules.sh" "$work/modules")
"$here/make-initramfs.sh" "$work/initramfs-$HIL_KVER.cpio.gz"

package=${HIL_PACKAGE:-}
if [ -z "${HIL_CHECKS:-}" ] && [ -f "$build/CPackConfig.cmake" ] && [ "${HIL_SYSTEMD:-1}" = 1 ]; then
    hil_say "building the Debian package (cpack)"
    (cd "$build" && cpack -G DEB >"$work/cpack.log" 2>&1) ||
        { cat "$work/cpack.log" >&2; hil_say "cpack failed"; exit 1; }
    package=$(ls -t "$build"/package/mirror_*.deb | head -1)
    # shellcheck disable=SC2086,SC2116 # the words on one line
    checks=$(echo $package_checks)
    if [ "${HIL_SCENARIO:-}" = hotplug ]; then
        checks=$(echo $hotplug_checks)
        ((soak_minutes > 0)) && checks="$checks replug_soak"
    fi
fi

results=$work/results${HIL_SCENARIO:+-$HIL_SCENARIO}
rm -rf "$results"
mkdir -p "$results"
cat >"$results/hil.env" <<ENV
HIL_MODULES=$modules
HIL_BIN=$build/bin
HIL_SOURCE_DIR=$source_dir
HIL_ASAN_BIN=$asan_bin
HIL_CHECKS="$checks"
HIL_PACKAGE=$package
HIL_SERVICE_TYPE=${HIL_SERVICE_TYPE:-}
HIL_FLOOD_BYTES=${HIL_FLOOD_BYTES:-1048576}
HIL_SOAK_MINUTES=$soak_minutes
HIL_SOAK_PERIOD_S=${HIL_SOAK_PERIOD_S:-60}
HIL_CALIBRATION_REF_MS=$calibration_ref_ms
HIL_SCALE_MAX_PCT=$scale_max_pct
ENV

# systemd as PID 1 in the guest (HIL_SYSTEMD=0: a plain shell script as init, no units).
boot_args=
if [ "${HIL_SYSTEMD:-1}" = 1 ]; then
    boot_args="hil_systemd=1 systemd.unit=hil.target systemd.show_status=0"
fi

qemu_log=$results/qemu.log
hil_say "booting $HIL_VMLINUZ in qemu (TCG), log: $qemu_log"
start=$SECONDS
# serial0 = the kernel console and the check lines (stdio); serial1 = the mirror's console (pty).
timeout --kill-after=10 "$timeout_max_s" qemu-system-x86_64 \
    -accel tcg -cpu max -m 2G -smp 2 -nographic -vga none -no-reboot \
    -kernel "$HIL_VMLINUZ" -initrd "$work/initramfs-$HIL_KVER.cpio.gz" \
    -append "console=ttyS0 panic=-1 loglevel=4 hil_script=$here/guest-test.sh hil_results=/hil-results $boot_args" \
    -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
    -virtfs "local,path=$results,mount_tag=results,security_model=none" \
    -serial mon:stdio -serial pty \
    </dev/null >"$qemu_log" 2>&1 &
qemu=$!

# flood MAX: random bytes on fd 4 (the pty) in 4 KiB pieces, as many as the guest takes in 15 s
# at the rate measured over the first 5 s (a write blocks while the guest's UART is full), at
# least 64 KiB, at most MAX, and ended at 60 s whatever the rate (console_round allows for that);
# prints what it wrote.
flood() {
    local max=$1 min=65536 piece=4096 written=0 total=$1 rate=
    local t0=${EPOCHREALTIME/./} us
    while ((written < total)); do
        head -c "$piece" /dev/urandom >&4 || break
        written=$((written + piece))
        us=$((${EPOCHREALTIME/./} - t0))
        if [ -z "$rate" ] && ((us >= 5000000)); then
            rate=$((written * 1000000 / us))  # bytes per second
            total=$((rate * 15))
            ((total >= min)) || total=$min
            ((total <= max)) || total=$max
        fi
        ((us < 60000000 || written < min)) || break
    done
    us=$((${EPOCHREALTIME/./} - t0))
    echo "flood of $written bytes written in $((us / 1000000)).$((us / 100000 % 10)) s" \
        "(${rate:+$((rate / 1024)) KiB/s over the first 5 s; }sized for 15 s, 64 KiB..$((max / 1024)) KiB)"
}

# The host end of ttyS1, one round at a time: once the guest wrote console.send (lines to type;
# "@flood N" = at most N random bytes, see flood), console.expect (an extended regex) and
# console.wait (seconds), and created console.ready (which the driver removes), type each line
# with Enter, keep everything read in console.txt until the pattern shows up (or the wait is
# over), then create console.done.
console_driver() {
    local pty line wait
    while kill -0 $qemu 2>/dev/null; do
        if [ ! -e "$results/console.ready" ]; then
            sleep 0.5
            continue
        fi
        rm -f "$results/console.ready"  # taken: one round per ready
        pty=$(grep -o 'redirected to /dev/pts/[0-9]*' "$qemu_log" | head -1 | cut -d' ' -f3)
        if [ -z "$pty" ]; then
            echo "no pty in $qemu_log" >"$results/console.txt"
            touch "$results/console.done"
            continue
        fi
        wait=$(cat "$results/console.wait" 2>/dev/null || echo 60)
        stty -F "$pty" raw -echo
        exec 4<>"$pty"
        cat <&4 >"$results/console.txt" &
        local reader=$!
        while IFS= read -r line; do
            case $line in
            '@flood '*) flood "${line#@flood }" >"$results/console.flood" ;;
            *) printf '%s\r' "$line" >&4 ;;
            esac
            sleep 1
        done <"$results/console.send"
        local until=$((SECONDS + wait))
        while ((SECONDS < until)); do
            grep -aqE "$(cat "$results/console.expect")" "$results/console.txt" && break
            sleep 0.5
        done
        sleep 1
        kill $reader 2>/dev/null
        wait $reader 2>/dev/null || true  # cat ends on SIGTERM (143)
        exec 4>&-
        touch "$results/console.done"
    done
}
console_driver &
driver=$!

# The run's limit: boot_limit_s until the guest's calibration line, then timeout_s stretched by
# its scale. Past it the machine is stopped (stopped_at_limit says so).
# Once the guest has logged "guest done" its checks and their results are complete; the power-off
# that follows takes seconds, but once (2026-12-07, hotplug, all checks passed at 215 s) the
# machine never powered off and the run waited 900 s for its limit. poweroff_grace_s after
# "guest done" the machine is stopped, said in one line, and the run judged on its checks.
poweroff_grace_s=${HIL_POWEROFF_GRACE_S:-60}
calibration= limit=$boot_limit_s stopped_at_limit=0 done_at=0 stopped_after_done=0
while kill -0 $qemu 2>/dev/null; do
    if ((done_at == 0)) && grep -q ' guest done$' "$results/guest.log" 2>/dev/null; then
        done_at=$SECONDS
    fi
    if ((done_at > 0 && SECONDS - done_at > poweroff_grace_s)); then
        stopped_after_done=1
        kill $qemu 2>/dev/null || true
        break
    fi
    if [ -z "$calibration" ]; then
        calibration=$(grep -ao 'HIL CALIBRATION .*' "$qemu_log" | tr -d '\r' | head -1) || true
        if [ -n "$calibration" ]; then
            scale=$(sed -E 's/.*scale_pct=([0-9]+).*/\1/' <<<"$calibration")
            limit=$((SECONDS - start + timeout_s * scale / 100))
            hil_say "${calibration#HIL CALIBRATION }: the run's limit is $limit s"
        fi
    fi
    if ((SECONDS - start > limit)); then
        stopped_at_limit=1
        kill $qemu 2>/dev/null || true
        break
    fi
    sleep 1
done
status=0
wait $qemu || status=$?
kill $driver 2>/dev/null || true
wait $driver 2>/dev/null || true
elapsed=$((SECONDS - start))

grep -ao 'HIL \(PASS\|FAIL\|SKIP\|SCRIPT\) .*' "$qemu_log" | tr -d '\r' >"$results/summary.txt" || true
# The snapshot from the DRM display path, read back through the results share: the display's
# size and a camera picture (vimc's colour bars), not a blank frame or the "camera unavailable" screen.
if grep -qx 'HIL PASS snapshot_drm' "$results/summary.txt"; then
    checks="$checks snapshot_image"
    if why=$("$here/png-check.py" "$results/snapshot-drm.png" $display_size 2>&1); then
        echo "HIL PASS snapshot_image" >>"$results/summary.txt"
        hil_say "snapshot: $why"
    else
        echo "HIL FAIL snapshot_image: $(echo $why)" >>"$results/summary.txt"
    fi
fi
[ -s "$results/flood.txt" ] && hil_say "$(cat "$results/flood.txt")"
[ -s "$results/hotplug-ready.txt" ] && hil_say "boot without devices: $(cat "$results/hotplug-ready.txt")"
[ -s "$results/soak.txt" ] && hil_say "replug soak (memory before each unplug):" && cat "$results/soak.txt" >&2
cat "$results/summary.txt"
# How long each check took (guest seconds), and the check that never ended if one did not.
grep -ao 'HIL TIME [^ ]* [0-9.]*' "$qemu_log" | tr -d '\r' >"$results/times.txt" || true
hil_say "check times (s): $(awk '{printf "%s%s %s", (NR > 1 ? ", " : ""), $3, $4}' "$results/times.txt")"
running=$(grep -ao 'HIL START [^ ]*' "$qemu_log" | tr -d '\r' | tail -1 | cut -d' ' -f3) || true
fail=0
if ((stopped_at_limit)); then
    hil_say "stopped the machine at its limit of ${limit}s (${calibration:-no calibration line by then})"
    fail=1
elif ((stopped_after_done)); then
    hil_say "the machine did not power off within ${poweroff_grace_s}s of its checks ending; stopped it"
elif ((status != 0)); then
    hil_say "qemu exited with $status after ${elapsed}s (124 = the hard stop at ${timeout_max_s}s)"
    fail=1
fi
if [ -n "$running" ] && ! grep -q "^HIL TIME $running " "$results/times.txt"; then
    hil_say "check $running was still running"
fi
grep -q '^HIL FAIL' "$results/summary.txt" && fail=1
for c in $checks; do
    grep -qx "HIL PASS $c" "$results/summary.txt" || { hil_say "missing: HIL PASS $c"; fail=1; }
done
if ((fail)); then
    hil_say "FAILED in ${elapsed}s; guest log:"
    tail -n 40 "$results/guest.log" >&2 2>/dev/null || true
    hil_say "last lines of the machine's console:"
    tail -n 30 "$qemu_log" | tr -d '\r' >&2
    exit 1
fi
hil_say "all $(wc -w <<<"$checks") checks passed in ${elapsed}s (${calibration#HIL CALIBRATION }, limit ${limit}s)"
