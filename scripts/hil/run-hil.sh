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
timeout_s=${HIL_TIMEOUT:-290}

# The checks the guest runs, in order; each must print "HIL PASS name" (HIL_CHECKS="a b": only
# those). With packaging configured (cmake/packaging.cmake) the .deb is built, installed in the
# guest right after the modules (the postinst starts the unit, whose ~40 s start-up under TCG
# then overlaps the device checks), and the unit must reach READY=1 (service_ready); the service
# runs the same binary as mirror_headless, which it replaces; it owns ttyS1 (console.serial), so
# console_selftest (status and selftest typed on the mirror's console) replaces serial_port (a
# shell responder). HIL_SERVICE_TYPE=simple checks the unit with a firmware that does not send
# READY/WATCHDOG yet.
device_checks="camera_listed camera_capture display_connected gpio_sim gpio_edges serial_port"
checks=${HIL_CHECKS:-"modules $device_checks mirror_headless"}

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
    checks="modules package_installed ${device_checks/serial_port/console_selftest} service_ready"
fi

results=$work/results
rm -rf "$results"
mkdir -p "$results"
cat >"$results/hil.env" <<ENV
HIL_MODULES=$modules
HIL_BIN=$build/bin
HIL_SOURCE_DIR=$(cd "$here/../.." && pwd)
HIL_CHECKS="$checks"
HIL_PACKAGE=$package
HIL_SERVICE_TYPE=${HIL_SERVICE_TYPE:-}
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
timeout --kill-after=10 "$timeout_s" qemu-system-x86_64 \
    -accel tcg -cpu max -m 2G -smp 2 -nographic -vga none -no-reboot \
    -kernel "$HIL_VMLINUZ" -initrd "$work/initramfs-$HIL_KVER.cpio.gz" \
    -append "console=ttyS0 panic=-1 loglevel=4 hil_script=$here/guest-test.sh hil_results=/hil-results $boot_args" \
    -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
    -virtfs "local,path=$results,mount_tag=results,security_model=none" \
    -serial mon:stdio -serial pty \
    </dev/null >"$qemu_log" 2>&1 &
qemu=$!

# The host end of ttyS1: once the guest wrote console.send (lines to type) and console.expect
# (an extended regex) and created console.ready, type each line with Enter, keep everything read
# in console.txt until the pattern shows up (or 60 s), then create console.done.
console_driver() {
    local pty deadline=$((SECONDS + timeout_s)) line
    until [ -e "$results/console.ready" ]; do
        kill -0 $qemu 2>/dev/null && ((SECONDS < deadline)) || return 0
        sleep 0.5
    done
    pty=$(grep -o 'redirected to /dev/pts/[0-9]*' "$qemu_log" | head -1 | cut -d' ' -f3)
    [ -n "$pty" ] || { echo "no pty in $qemu_log" >"$results/console.txt"; touch "$results/console.done"; return 0; }
    stty -F "$pty" raw -echo
    exec 4<>"$pty"
    cat <&4 >"$results/console.txt" &
    local reader=$!
    while IFS= read -r line; do
        printf '%s\r' "$line" >&4
        sleep 1
    done <"$results/console.send"
    for _ in $(seq 120); do
        grep -aqE "$(cat "$results/console.expect")" "$results/console.txt" && break
        sleep 0.5
    done
    sleep 1
    kill $reader 2>/dev/null
    exec 4>&-
    touch "$results/console.done"
}
console_driver &
driver=$!

status=0
wait $qemu || status=$?
kill $driver 2>/dev/null || true
wait $driver 2>/dev/null || true
elapsed=$((SECONDS - start))

grep -ao 'HIL \(PASS\|FAIL\|SKIP\|SCRIPT\) .*' "$qemu_log" | tr -d '\r' >"$results/summary.txt" || true
cat "$results/summary.txt"
fail=0
((status == 0)) || { hil_say "qemu exited with $status after ${elapsed}s (124 = timeout ${timeout_s}s)"; fail=1; }
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
hil_say "all $(wc -w <<<"$checks") checks passed in ${elapsed}s"
