#!/bin/bash
# The test inside the emulated machine (run by the initramfs as PID 1's only child; the machine
# powers off when it returns). $1 = the results share; $1/hil.env (written by the host) names the
# module tree, the build tree and the checks to run.
#
# Each check is a function check_NAME that prints nothing on success and the reason on failure;
# run_check prints one line "HIL PASS NAME" or "HIL FAIL NAME: why" for the host to collect.
# Adding a check = one function + its name in HIL_CHECKS (hil.env, from run-hil.sh).
set -uo pipefail
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
R=${1:?results directory}
# shellcheck source=/dev/null
. "$R/hil.env"
KVER=$(uname -r)
LOG=$R/guest.log
exec 3>>"$LOG"

log() { printf '%s %s\n' "$(cut -d' ' -f1 /proc/uptime)" "$*" >&3; }

# Guest time in milliseconds (bash's own clock: no process to start).
now_ms() { local t=${EPOCHREALTIME/./}; echo $((t / 1000)); }

# Every deadline is in seconds as measured on the reference machine (an idle 2-core host of
# this kind) and is stretched by HIL_SCALE_PCT, which calibrate sets from the guest's time to
# start the mirror (100 = as fast as the reference; never less).
HIL_SCALE_PCT=100
scaled() { echo $((($1 * HIL_SCALE_PCT + 99) / 100)); }

# Each check's start and duration go to ttyS0 as well ("HIL START", "HIL TIME"): when the
# machine is stopped at its limit, the host can say which check was running and what took long.
run_check() {
    local name=$1 why t0
    log "check $name"
    echo "HIL START $name"
    t0=$(now_ms)
    if why=$("check_$name" 2>&1); then
        echo "HIL PASS $name" | tee -a "$R/checks.txt"
    else
        why=$(printf '%s' "$why" | tr '\n' ' ' | cut -c1-300)
        echo "HIL FAIL $name: ${why:-failed}" | tee -a "$R/checks.txt"
    fi
    local ms=$(($(now_ms) - t0))
    printf 'HIL TIME %s %d.%01d\n' "$name" $((ms / 1000)) $((ms % 1000 / 100))
}

# wait_for SECONDS COMMAND...: poll until COMMAND succeeds; false once SECONDS (scaled) passed.
wait_for() {
    local deadline=$((SECONDS + $(scaled "$1")))
    shift
    until "$@" >/dev/null 2>&1; do
        ((SECONDS < deadline)) || return 1
        sleep 0.2
    done
}

# --- machine set-up ---------------------------------------------------------------------------

# The out-of-tree modules and the host's depmod index go into the tmpfs overlay of /lib/modules.
check_modules() {
    local d=/lib/modules/$KVER
    mkdir -p "$d/extra" && cp "$HIL_MODULES/extra/"*.ko "$d/extra/" &&
        cp "$HIL_MODULES/root/lib/modules/$KVER/"modules.* "$d/" || return 1
    # udevd first: the devices the modules create then get their udev records (libcamera
    # enumerates cameras through udev), without a slow trigger of every device in the machine.
    if ! pidof systemd-udevd >/dev/null; then  # under systemd it is already running
        /lib/systemd/systemd-udevd --daemon >>"$LOG" 2>&1 || { echo "systemd-udevd did not start"; return 1; }
    fi
    modprobe vimc && modprobe vkms && modprobe gpio-sim || return 1
    log "modules loaded"
    udevadm trigger --action=add --subsystem-match=media --subsystem-match=video4linux \
        --subsystem-match=drm --subsystem-match=gpio --subsystem-match=tty &&
        udevadm settle --timeout="$(scaled 60)" || { echo "udevadm settle timed out"; return 1; }
    log "udev settled"
    local m
    for m in vimc vkms gpio_sim; do
        grep -q "^$m " /proc/modules || { echo "$m not loaded"; return 1; }
    done
}

# --- camera (vimc through libcamera) ----------------------------------------------------------

check_camera_listed() {
    local out
    out=$(cam -l 2>&1)
    echo "$out" >"$R/cam-list.txt"
    grep -q 'platform/vimc.0' <<<"$out" || { echo "cam -l does not list vimc: $out"; return 1; }
}

check_camera_capture() {
    rm -f "$R"/cam-frame-*.bin
    timeout "$(scaled 60)" cam -c 1 -C3 -F"$R/cam-frame-#.bin" >"$R/cam-capture.txt" 2>&1 ||
        { echo "cam capture failed: $(tail -3 "$R/cam-capture.txt")"; return 1; }
    local n
    n=$(find "$R" -name 'cam-frame-*.bin' -size +1k | wc -l)
    ((n >= 3)) || { echo "expected 3 frames, got $n"; return 1; }
}

# --- display (vkms) ---------------------------------------------------------------------------

check_display_connected() {
    [ -c /dev/dri/card0 ] || { echo "no /dev/dri/card0"; return 1; }
    local s found=
    for s in /sys/class/drm/card*-*/status; do
        [ -e "$s" ] || continue
        echo "$s $(cat "$s") $(head -1 "${s%/status}/modes" 2>/dev/null)" >>"$R/drm-connectors.txt"
        [ "$(cat "$s")" = connected ] && found=$s
    done
    [ -n "$found" ] || { echo "no connected DRM connector: $(cat "$R/drm-connectors.txt" 2>/dev/null)"; return 1; }
    # vkms registers a bare platform device named after itself (no driver binds to it).
    local device
    device=$(basename "$(readlink -f /sys/class/drm/card0/device)")
    [ "$device" = vkms ] || { echo "card0 is the device '$device', not vkms"; return 1; }
}

# --- GPIO (gpio-sim, two lines: the buttons) --------------------------------------------------

# The chip's names, kept in a file: each check runs in its own subshell.
gpio_names() { . "$R/gpio.env" 2>/dev/null; }

check_gpio_sim() {
    local cfg=/sys/kernel/config
    mountpoint -q "$cfg" || mount -t configfs none "$cfg" || return 1
    local c=$cfg/gpio-sim/hil
    mkdir -p "$c/bank0" && echo 2 >"$c/bank0/num_lines" || return 1
    mkdir -p "$c/bank0/line0" "$c/bank0/line1" &&
        echo button-a >"$c/bank0/line0/name" && echo button-b >"$c/bank0/line1/name" || return 1
    echo 1 >"$c/live" || { echo "gpio-sim chip did not go live"; return 1; }
    printf 'GPIO_CHIP=%s\nGPIO_DEV=%s\n' "$(cat "$c/bank0/chip_name")" "$(cat "$c/dev_name")" >"$R/gpio.env"
    gpio_names
    gpiodetect >>"$R/gpio.txt" 2>&1
    gpioinfo "$GPIO_CHIP" >>"$R/gpio.txt" 2>&1
    grep -q button-a "$R/gpio.txt" || { echo "gpioinfo does not show the line names"; return 1; }
}

# gpio_pull LINE up|down: what a pressed/released button does to the input.
gpio_pull() { echo "pull-$2" >"/sys/devices/platform/$GPIO_DEV/$GPIO_CHIP/sim_gpio$1/pull"; }

check_gpio_edges() {
    local GPIO_CHIP="" GPIO_DEV=""
    gpio_names
    [ -n "$GPIO_CHIP" ] || { echo "no gpio-sim chip"; return 1; }
    gpio_pull 0 down
    [ "$(gpioget "$GPIO_CHIP" 0)" = 0 ] || { echo "line 0 not low after pull-down"; return 1; }
    gpiomon --num-events=2 --rising-edge --falling-edge "$GPIO_CHIP" 0 >"$R/gpiomon.txt" 2>&1 &
    local mon=$!
    sleep 1  # gpiomon must hold the line before the edges
    gpio_pull 0 up
    sleep 0.3
    gpio_pull 0 down
    wait_for 10 bash -c "! kill -0 $mon" || { kill $mon; echo "gpiomon saw no edges"; return 1; }
    grep -q RISING "$R/gpiomon.txt" && grep -q FALLING "$R/gpiomon.txt" ||
        { echo "edges missing: $(cat "$R/gpiomon.txt")"; return 1; }
}

# --- serial console (ttyS1 <-> the host's pty) ------------------------------------------------

# Until the mirror's serial console is wired: a responder proves the port works both ways. The
# host (run-hil.sh) waits for console.ready, writes "ping N" lines and expects "pong N".
check_serial_port() {
    [ -c /dev/ttyS1 ] || { echo "no /dev/ttyS1"; return 1; }
    # Canonical mode with CR->NL: a terminal's Enter arrives as CR alone.
    stty -F /dev/ttyS1 115200 cs8 -cstopb -parenb sane -echo || return 1
    (
        exec </dev/ttyS1 >/dev/ttyS1
        while read -r -t 30 line; do
            log "ttyS1 got: $line"
            printf 'pong %s\n' "${line#ping }"
            [ "$line" = "ping 3" ] && break
        done
    ) &
    local responder=$!
    printf 'ping 1\nping 2\nping 3\n' >"$R/console.send"
    echo 'pong 3' >"$R/console.expect"
    touch "$R/console.ready"
    wait_for 60 test -e "$R/console.done" || { kill $responder 2>/dev/null; echo "host never finished"; return 1; }
    kill $responder 2>/dev/null
    grep -q 'pong 3' "$R/console.txt" || { echo "no reply on the serial port: $(head -c 200 "$R/console.txt")"; return 1; }
}

# --- the device code under AddressSanitizer ----------------------------------------------------

# The platform tests of the AddressSanitizer + UBSan build (HIL_ASAN_BIN) on the real devices,
# before the service owns them: libcamera capture and reopen, the camera unplugged mid-run (vimc
# unbound; bound again here once that process ended), the DRM mode set, flips, a mode set refused while another process
# is master and then retried. Any ASan/UBSan report or leak (LeakSanitizer at exit; Mesa's and
# LLVM's process-lifetime caches suppressed, as on the host) fails the check.
check_asan_devices() {
    local t=$HIL_ASAN_BIN/devices_live_test out=$R/asan-devices.txt
    [ -x "$t" ] || { echo "no $t"; return 1; }
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        LSAN_OPTIONS="suppressions=$HIL_SOURCE_DIR/tests/sanitizers/lsan.supp:print_suppressions=0" \
        LIBCAMERA_LOG_LEVELS="*:WARN" MIRROR_TEST_UNPLUG_LIBCAMERA=vimc:vimc.0 timeout "$(scaled 240)" "$t" --gtest_filter='-*V4l2*' \
        >"$out" 2>&1
    local rc=$?
    log "asan devices_live_test exit $rc"
    # The camera back for the service (the process that lost it could not take it back).
    [ -e /sys/bus/platform/drivers/vimc/vimc.0 ] || echo vimc.0 >/sys/bus/platform/drivers/vimc/bind ||
        { echo "vimc.0 could not be bound again"; return 1; }
    udevadm settle --timeout="$(scaled 30)"
    ((rc == 0)) || { echo "exit $rc: $(grep -aE 'ERROR|Failure|FAILED' "$out" | head -3)"; return 1; }
    ! grep -aq 'SKIPPED \]' "$out" || { echo "skipped: $(grep -a 'SKIPPED \]' "$out" | head -3)"; return 1; }
    grep -aq 'PASSED .*5 tests' "$out" || { echo "not 5 tests passed: $(tail -2 "$out")"; return 1; }
}

# --- the firmware -----------------------------------------------------------------------------

check_mirror_headless() {
    local out=$R/mirror-headless
    rm -rf "$out"
    # Small frames: llvmpipe under TCG renders ~70x slower than on the host.
    timeout "$(scaled 120)" "$HIL_BIN/mirror" --source synthetic --display "headless:$out" --frames 10 \
        --set source.width=320 --set source.height=240 --set display.width=320 \
        --set display.height=240 --set display.snapshot_every=5 \
        --set console.stdin=false --set "state.dir=\"$R/state\"" \
        >"$R/mirror-headless.log" 2>&1 </dev/null ||
        { echo "mirror exited $?: $(tail -3 "$R/mirror-headless.log")"; return 1; }
    ls "$out"/*.png >/dev/null 2>&1 || { echo "no snapshot in $out"; return 1; }
}

# console_round WAIT LINE...: type LINEs on the mirror's console (ttyS1) from the host, one a
# second ("@flood N": random bytes instead of a line, at most N, sized by the host), and keep
# what comes back in $R/console-NAME.txt (NAME = the caller's check) once the last reply matches
# $expect (an extended regex) or WAIT (scaled) seconds passed. One round at a time; the host's
# console_driver does the typing.
console_round() {
    local wait=$1 name=${FUNCNAME[1]#check_} typing=$(($# + 30)) line
    shift
    for line; do
        # The host ends a flood within 60 s of its own clock (run-hil.sh, flood).
        [[ $line == '@flood '* ]] && typing=$((typing + 60))
    done
    # ready and done first: the host starts a round on console.ready alone.
    rm -f "$R/console.ready" "$R/console.done"
    rm -f "$R"/console.*
    printf '%s\n' "$@" >"$R/console.send"
    printf '%s\n' "$expect" >"$R/console.expect"
    scaled "$wait" >"$R/console.wait"
    touch "$R/console.ready"
    # The host's typing runs on its own clock; the reply's wait is stretched with the guest's.
    local deadline=$((SECONDS + typing + $(scaled "$wait")))
    until [ -e "$R/console.done" ]; do
        ((SECONDS < deadline)) || { echo "host never finished"; return 1; }
        sleep 0.2
    done
    # Without CRs and the console's prompts ("> "), which precede the first line of each reply.
    tr -d '\r' <"$R/console.txt" | sed 's/^\(> \)*//' >"$R/console-$name.txt"
    CONSOLE=$R/console-$name.txt
}

# unit_show PROPERTY: one property of mirror.service.
unit_show() { systemctl show -p "$1" --value mirror.service; }

# journal_has TEXT [N]: the service's journal holds TEXT at least N (1) times.
journal_has() {
    (($(journalctl --no-pager -q -o cat -u mirror.service 2>/dev/null | grep -acF "$1") >= ${2:-1}))
}

# The mirror's own console on ttyS1 (the service's drop-in sets console.serial): the host types
# `status`, `overlay` and `selftest`; status names the libcamera source and the DRM display, every
# selftest line (camera, display, state, faces, overlays, gpio) must PASS.
check_console_selftest() {
    # selftest asks for recent frames: wait for READY=1 (the unit turns active after the first
    # frame is shown), which under TCG comes ~60 s after the postinst started it.
    wait_for 150 bash -c '[ "$(systemctl is-active mirror.service)" = active ]' ||
        { echo "mirror.service not active: $(systemctl is-active mirror.service)"; return 1; }
    log "mirror.service active"
    local expect='selftest: '
    console_round 60 status overlay selftest || return 1
    local t=$CONSOLE
    grep -q '^source: .*libcamera' "$t" || { echo "status shows no libcamera source: $(grep -a '^source' "$t")"; return 1; }
    grep -q '^display: drm' "$t" || { echo "status shows no drm display: $(grep -a '^display' "$t")"; return 1; }
    grep -q '^overlay: ' "$t" || { echo "no overlay reply"; return 1; }
    grep -q 'selftest: all PASS' "$t" ||
        { echo "selftest did not pass: $(grep -a 'FAIL\|selftest\|error' "$t" | head -5 | tr '\n' ' ')"; return 1; }
    local n
    for n in camera display state faces overlays gpio; do
        grep -q "^PASS $n: " "$t" || { echo "selftest has no 'PASS $n'"; return 1; }
    done
    grep -aq 'error:' "$t" && { echo "the console answered an error: $(grep -a 'error:' "$t" | head -2)"; return 1; }
    grep '^overlay: ' "$t" | head -1 >"$R/overlay-before.txt"
    return 0
}

# The unit reached READY (Type=notify) as user mirror, without restarts so far.
check_service_ready() {
    [ "$(cat /proc/1/comm)" = systemd ] || { echo "PID 1 is not systemd (HIL_SYSTEMD=0)"; return 1; }
    local ActiveState="" NRestarts="" MainPID=""
    eval "$(systemctl show -p ActiveState,NRestarts,MainPID mirror.service)"
    local state=$ActiveState restarts=$NRestarts pid=$MainPID
    [ "$state" = active ] || { echo "not active: $state"; return 1; }
    [ "$restarts" = 0 ] || { echo "restarted $restarts times"; return 1; }
    [ "$(stat -c %U "/proc/$pid")" = mirror ] || { echo "main process $pid does not run as user mirror"; return 1; }
}

# A short press of button 1 (gpio-sim line 0 pulled low, beyond the 30 ms debounce, short of the
# 2 s long press) selects the next overlay: the log says so and `overlay` differs. The hold is
# 150 ms of the guest's clock stretched with the calibration (at most 900 ms): the kernel's v1
# line events tell a falling from a rising edge by the level their interrupt thread reads, so
# the line must still be low when that thread runs, which on a slow host can be late. The hold
# is timed by bash's own `read -t` (no process to start: under TCG starting `sleep` alone can
# take longer than a long press). The mirror dates both edges by the kernel's stamps, so the
# press keeps its length however late its frame loop reads them (the fault runs starting beside
# it can stall a frame for seconds).
check_button_press() {
    local GPIO_CHIP="" GPIO_DEV="" timer=/tmp/hil-timer t0 held hold_ms
    gpio_names
    [ -p $timer ] || mkfifo $timer
    exec 7<>$timer
    hold_ms=$(scaled 150)
    ((hold_ms <= 900)) || hold_ms=900
    t0=$(now_ms)
    gpio_pull 0 down
    read -r -t "$(printf '%d.%03d' $((hold_ms / 1000)) $((hold_ms % 1000)))" -u 7
    gpio_pull 0 up
    held=$(($(now_ms) - t0))
    exec 7>&-
    log "button 1 held for $held ms"
    if ! wait_for 20 journal_has 'button 1 short press: next'; then
        journalctl -q -o cat -u mirror.service | grep -a 'button' >"$R/button-journal.txt"
        echo "no 'button 1 short press: next' in the journal within $(scaled 20) s of a $held ms press; its button lines (results/button-journal.txt): $(tail -2 "$R/button-journal.txt" | cut -c1-100 | tr '\n' '|')"
        return 1
    fi
    local expect='overlay: '
    console_round 20 overlay || return 1
    local before after
    before=$(cat "$R/overlay-before.txt" 2>/dev/null)
    after=$(grep -a '^overlay: ' "$CONSOLE" | head -1)
    [ -n "$after" ] || { echo "no reply to overlay"; return 1; }
    [ "$before" != "$after" ] || { echo "overlay unchanged after the press: $after"; return 1; }
    log "overlay: '$before' -> '$after'"
}

# `snapshot` on the DRM display: the frame read back before the page flip, written as a PNG in
# the state folder by user mirror; copied to the results for the host to check its pixels.
check_snapshot_drm() {
    # The path comes with a later frame, in place of the waiting prompt
    # ("\rsnapshot: wrote /...png").
    local expect='snapshot: wrote /.*\.png'
    console_round 30 snapshot || return 1
    local png
    png=$(grep -aoE 'snapshot: wrote /[^ ]*\.png' "$CONSOLE" | head -1 | cut -d' ' -f3)
    [ -n "$png" ] || { echo "no snapshot path: $(grep -a snapshot "$CONSOLE" | tr '\n' ' ')"; return 1; }
    [ -f "$png" ] || { echo "$png missing"; return 1; }
    [ "$(stat -c %U "$png")" = mirror ] || { echo "$png is not owned by user mirror"; return 1; }
    cp "$png" "$R/snapshot-drm.png"
}

# The console's bug report, written by the service itself (user mirror): the tarball names the
# unit's journal of this boot, with the service's own lines in it, not a permissions notice.
check_bug_report() {
    local expect='bug-report: (wrote|failed)'
    console_round 90 bug-report || return 1
    local tgz
    tgz=$(grep -aoE 'bug-report: wrote /[^ ]*\.tar\.gz' "$CONSOLE" | head -1 | cut -d' ' -f3)
    [ -n "$tgz" ] || { echo "no bug report: $(grep -a 'bug-report' "$CONSOLE" | tr '\n' ' ')"; return 1; }
    mkdir -p "$R/bug-report" && tar -xzf "$tgz" -C "$R/bug-report" || { echo "cannot unpack $tgz"; return 1; }
    local journal
    journal=$(find "$R/bug-report" -name journal.txt | head -1)
    [ -n "$journal" ] || { echo "no journal.txt in $tgz"; return 1; }
    grep -q 'running: source libcamera' "$journal" ||
        { echo "journal.txt holds no line of the service: $(head -c 300 "$journal" | tr '\n' ' ')"; return 1; }
}

# The camera unplugged while the mirror runs (vimc unbound from its driver): libcamera 0.0.3
# cannot let go of it, so the mirror says so once and exits for systemd to start it again; the
# camera is bound again and the new process reaches READY and delivers frames.
check_camera_replug() {
    local drv=/sys/bus/platform/drivers/vimc
    [ -e "$drv/vimc.0" ] || { echo "vimc.0 not bound to vimc"; return 1; }
    echo vimc.0 >"$drv/unbind" || { echo "cannot unbind vimc.0"; return 1; }
    log "vimc.0 unbound"
    local gone='camera vanished; libcamera needs a new process'
    wait_for 30 journal_has "$gone"
    local seen=$?
    echo vimc.0 >"$drv/bind" || { echo "cannot bind vimc.0 again"; return 1; }
    udevadm settle --timeout="$(scaled 30)"
    log "vimc.0 bound again"
    ((seen == 0)) || { echo "no '$gone' in the journal: $(journalctl -q -o cat -u mirror.service | tail -3)"; return 1; }
    wait_for 150 bash -c '(($(systemctl show -p NRestarts --value mirror.service) >= 1)) &&
        [ "$(systemctl is-active mirror.service)" = active ]' ||
        { echo "not back: $(systemctl show -p ActiveState,SubState,Result,NRestarts mirror.service | tr '\n' ' ')"; return 1; }
    log "mirror.service active again"
    journalctl --no-pager -u mirror.service >"$R/service-journal.txt" 2>&1
    (($(grep -acF "$gone" "$R/service-journal.txt") == 1)) || { echo "the unplug was logged more than once"; return 1; }
    grep -q 'Main process exited, code=exited, status=3/' "$R/service-journal.txt" ||
        { echo "the mirror did not exit with code 3 (source)"; return 1; }
    # The first frames of a new process are slow under TCG (shaders compiled, ~2 s each), and
    # selftest wants a frame within the last 2 s: ask up to three times.
    local expect='selftest: ' try
    for try in 1 2 3; do
        console_round 60 overlay selftest || return 1
        grep -q '^PASS camera: ' "$CONSOLE" && break
        ((try < 3)) || { echo "camera not back: $(grep -a 'camera' "$CONSOLE" | head -2)"; return 1; }
        sleep 2
    done
    # What the new process wears (the choice is kept in the state folder): button_press changes it.
    grep '^overlay: ' "$CONSOLE" | head -1 >"$R/overlay-before.txt"
}

# A second mirror run directly (root, synthetic scene) on the same DRM card while the service
# holds it, with a GPIO chip and a serial port that do not exist. Started in the background
# (start-up under TCG takes ~30 s) and checked by display_fault, gpio_absent, serial_absent.
check_fault_run_start() {
    # An impossible mode: the display cannot be made; one line naming it, exit code 4 (display).
    # In the background too: both start-ups (~20 s and ~45 s under TCG) overlap the flood.
    # Not on this check's stdout: the check's caller would wait for it.
    (
        rc=0
        timeout "$(scaled 90)" "$HIL_BIN/mirror" --source synthetic --display drm --set 'display.mode="7777x7777"' \
            --set console.stdin=false --set buttons.enabled=false --set "state.dir=\"/tmp/hil-mode\"" \
            >"$R/mirror-badmode.log" 2>&1 </dev/null || rc=$?
        echo "$rc" >"$R/mirror-badmode.rc"
    ) >/dev/null 2>&1 &
    setsid "$HIL_BIN/mirror" --source synthetic --display drm --set 'display.mode="640x480"' \
        --set source.width=320 --set source.height=240 --set console.stdin=false \
        --set 'console.serial="/dev/ttyHIL-missing"' --set 'buttons.chip="gpiochip-missing"' \
        --set 'buttons.lines=[0, 1]' --set "state.dir=\"/tmp/hil-fault\"" \
        >"$R/mirror-faults.log" 2>&1 </dev/null &
    echo $! >"$R/mirror-faults.pid"
}

# The display cannot be made in the mode asked for: the mirror names the mode and the modes
# there are in one line and exits with the display's code (4) before anything else starts.
check_display_bad_mode() {
    wait_for 60 test -s "$R/mirror-badmode.rc" || { echo "the run did not end"; return 1; }
    local rc
    rc=$(cat "$R/mirror-badmode.rc")
    ((rc == 4)) || { echo "exit $rc, not 4: $(tail -2 "$R/mirror-badmode.log")"; return 1; }
    grep -q 'has no mode 7777x7777 (modes: ' "$R/mirror-badmode.log" ||
        { echo "the mode is not named: $(tail -2 "$R/mirror-badmode.log")"; return 1; }
}

# The serial console under a flood of random bytes typed on ttyS1 (the shell reads at most 4 KiB
# per frame and rejects binary lines); then `status` must still be answered. The host sizes the
# flood by the rate the guest takes bytes in over its first 5 s (15 s of it, at least 64 KiB, at
# most HIL_FLOOD_BYTES = 1 MiB): under TCG that rate is 20-35 KiB/s depending on the host, and
# the mirror reads a few frames' worth a second, so a fixed 1 MiB took 36 s on one host and over
# 200 s on another.
check_serial_flood() {
    [ "$(unit_show ActiveState)" = active ] || { echo "mirror.service not active"; return 1; }
    local expect='^source: ' restarts
    restarts=$(unit_show NRestarts)
    console_round 200 "@flood ${HIL_FLOOD_BYTES:-1048576}" '' status || return 1
    local flood rejected
    flood=$(cat "$R/console.flood" 2>/dev/null)
    echo "$flood" >"$R/flood.txt"  # for the host's summary (the next round clears console.*)
    rejected=$(grep -c 'binary data ignored' "$CONSOLE")
    if ! grep -q '^source: .*libcamera' "$CONSOLE"; then
        # A line typed while the guest's tty buffer was still full of noise is lost on the wire,
        # as on a real UART: a technician types it again.
        log "no status after the flood ($(wc -c <"$CONSOLE") bytes back): typing it again"
        console_round 60 '' status || return 1
    fi
    grep -q '^source: .*libcamera' "$CONSOLE" || { echo "no status after the flood ($flood; $(wc -c <"$CONSOLE") bytes back)"; return 1; }
    [ "$(unit_show NRestarts)" = "$restarts" ] || { echo "the service restarted during the flood"; return 1; }
    log "$flood, $rejected binary lines rejected"
}

# The direct run could not set its mode (the service is DRM master): one clear line, frames
# declined, retried; once the service stops, its mode set succeeds ("display is back").
check_display_fault() {
    local pid l=$R/mirror-faults.log
    pid=$(cat "$R/mirror-faults.pid" 2>/dev/null)
    [ -n "$pid" ] || { echo "no fault run"; return 1; }
    wait_for 90 grep -q 'mode set failed' "$l" ||
        { echo "no 'mode set failed' line: $(tail -3 "$l")"; kill "$pid" 2>/dev/null; return 1; }
    kill -0 "$pid" 2>/dev/null || { echo "the mirror exited after the failed mode set: $(tail -2 "$l")"; return 1; }
    log "fault run: mode set failed; stopping mirror.service"
    systemctl stop mirror.service
    wait_for 30 grep -q 'display is back' "$l"
    local back=$?
    kill -TERM "$pid" 2>/dev/null
    wait_for 20 bash -c "! kill -0 $pid" || { kill -KILL "$pid"; echo "the mirror did not stop on SIGTERM"; return 1; }
    ((back == 0)) || { echo "display not back after the service let go: $(tail -3 "$l")"; return 1; }
    (($(grep -c 'mode set failed' "$l") == 1)) || { echo "the mode set failure was logged $(grep -c 'mode set failed' "$l") times"; return 1; }
    grep -q 'stopped (stop requested)' "$l" || { echo "no clean stop: $(tail -2 "$l")"; return 1; }
}

# The same run without its GPIO chip and serial port: one warning each, the rest worked.
check_gpio_absent() {
    local l=$R/mirror-faults.log
    (($(grep -c 'buttons: .*; running without buttons' "$l") == 1)) ||
        { echo "expected one buttons warning: $(grep -a buttons "$l" | head -3)"; return 1; }
}

check_serial_absent() {
    local l=$R/mirror-faults.log
    (($(grep -c 'console: .*/dev/ttyHIL-missing.*; no serial console' "$l") == 1)) ||
        { echo "expected one console warning: $(grep -a console "$l" | head -3)"; return 1; }
}

# --- the Debian package and the service ----------------------------------------------------

# dpkg -i into the tmpfs overlay root, as on a clean machine: files, conffile, the user, the unit.
check_package_installed() {
    [ -f "${HIL_PACKAGE:-}" ] || { echo "no package (HIL_PACKAGE=${HIL_PACKAGE:-})"; return 1; }
    # The test decides what the mirror runs on (the postinst starts it under systemd): vimc through
    # libcamera at 320x240, vkms at 640x480, the buttons on the gpio-sim chip's lines 0 and 1
    # (pulled up: released), the console on ttyS1. Snapshots go to the state folder.
    local GPIO_CHIP="" GPIO_DEV=""
    gpio_names
    [ -n "$GPIO_CHIP" ] || { echo "no gpio-sim chip (check gpio_sim first)"; return 1; }
    gpio_pull 0 up && gpio_pull 1 up || return 1
    install_mirror_package "--source libcamera:0 --display drm --set 'display.mode=\"640x480\"' --set 'buttons.chip=\"$GPIO_CHIP\"' --set 'buttons.lines=[0, 1]' --set buttons.long_press_ms=2000"
}

# install_mirror_package ARGS: the drop-in (the service runs `mirror ARGS`, at 320x240 with the
# console on ttyS1, the start and watchdog limits stretched), then dpkg -i, whose postinst starts
# the unit; the package's files, conffile, user and groups are checked.
install_mirror_package() {
    mkdir -p /etc/systemd/system/mirror.service.d
    local watchdog
    watchdog=$(scaled 60)
    [ -z "${HIL_SERVICE_TYPE:-}" ] || watchdog=0  # a unit checked without READY/WATCHDOG support
    cat >/etc/systemd/system/mirror.service.d/hil.conf <<UNIT
[Service]
# Under TCG start-up (libraries over 9p, llvmpipe) takes ~50 s and frames are ~70x slower;
# both limits stretched with the calibration (HIL_SCALE_PCT=$HIL_SCALE_PCT).
TimeoutStartSec=$(scaled 150)
WatchdogSec=$watchdog
RestartSec=1
${HIL_SERVICE_TYPE:+Type=$HIL_SERVICE_TYPE}
ExecStart=
ExecStart=/usr/bin/mirror --config /etc/mirror/mirror.toml $1 --set source.width=320 --set source.height=240 --set console.stdin=false --set 'console.serial="/dev/ttyS1"'
UNIT
    # Installed as on a machine without this user, these files, or the unit enabled. dpkg's
    # database is the host's installed-package list (dependencies are checked against it) without
    # the per-package file lists: reading those thousands of files over 9p takes ~2 min under TCG.
    local admin=/var/lib/dpkg-hil
    # The guest's root is the host's, and a container host carries Docker's policy-rc.d, which
    # tells deb-systemd-invoke (rightly) not to start services. An appliance has none: the
    # overlay copy goes, the host's file stays.
    rm -f /usr/sbin/policy-rc.d
    mkdir -p "$admin/info" "$admin/updates" "$admin/triggers"
    cp /var/lib/dpkg/status /var/lib/dpkg/arch "$admin/"
    touch "$admin/available" "$admin/diversions" "$admin/statoverride"
    log "dpkg -i $HIL_PACKAGE"
    DEBIAN_FRONTEND=noninteractive dpkg --admindir="$admin" -i "$HIL_PACKAGE" >"$R/dpkg.log" 2>&1 ||
        { echo "dpkg -i failed: $(grep -v 'files list file' "$R/dpkg.log" | tail -3)"; return 1; }
    log "dpkg done"
    [ -x /usr/bin/mirror ] && [ -f /etc/mirror/mirror.toml ] &&
        [ -f /lib/systemd/system/mirror.service ] || { echo "files missing after dpkg -i"; return 1; }
    grep -qx /etc/mirror/mirror.toml "$admin/info/mirror.conffiles" || { echo "config is not a conffile"; return 1; }
    id mirror >"$R/mirror-user.txt" 2>&1 || { echo "no user mirror"; return 1; }
    local g groups
    groups=$(id -nG mirror)
    for g in video render gpio dialout systemd-journal; do
        grep -qw "$g" <<<"$groups" || { echo "user mirror not in group $g"; return 1; }
    done
    [ "$(systemctl is-enabled mirror.service 2>&1)" = enabled ] || { echo "mirror.service not enabled"; return 1; }
}

# --- boot without devices (HIL_SCENARIO=hotplug) -------------------------------------------------

# The module tree in place and udev running, but only the cores a board's kernel has loaded (V4L2,
# the media controller, DRM): no camera, no panel. The unit's DeviceAllow=char-video4linux etc.
# resolve through /proc/devices when it starts, so the cores must be there by then.
check_core_modules() {
    local d=/lib/modules/$KVER
    mkdir -p "$d/extra" && cp "$HIL_MODULES/extra/"*.ko "$d/extra/" &&
        cp "$HIL_MODULES/root/lib/modules/$KVER/"modules.* "$d/" || return 1
    pidof systemd-udevd >/dev/null || { echo "systemd-udevd not running"; return 1; }
    modprobe videodev && modprobe mc && modprobe drm || { echo "cannot load videodev, mc, drm"; return 1; }
    [ ! -e /dev/dri/card0 ] && ! ls /dev/video* >/dev/null 2>&1 || { echo "a camera or card is already there"; return 1; }
    log "core modules loaded, no camera or card"
}

# The package with `auto` for source and display and no buttons: the postinst starts it.
check_package_installed_bare() {
    install_mirror_package "--source auto --display auto --set display.width=640 --set display.height=480 --set 'display.mode=\"640x480\"' --set buttons.enabled=false"
}

# READY (the unit active) with the calm screen, no restart, both waits logged, no PNG written on
# its own into the state folder; the start-to-READY time is printed.
check_ready_without_devices() {
    wait_for 150 bash -c '[ "$(systemctl is-active mirror.service)" = active ]' ||
        { echo "not active: $(systemctl show -p ActiveState,SubState,NRestarts mirror.service | tr '\n' ' ')"; return 1; }
    local start ready
    start=$(unit_show ExecMainStartTimestampMonotonic)
    ready=$(unit_show ActiveEnterTimestampMonotonic)
    local ms=$(((ready - start) / 1000))
    echo "ready_ms=$ms scale_pct=$HIL_SCALE_PCT" >"$R/hotplug-ready.txt"
    echo "HIL FIGURE start_to_ready_ms=$ms" >/dev/console 2>/dev/null || true
    log "READY $ms ms after the start, without camera or panel"
    [ "$(unit_show NRestarts)" = 0 ] || { echo "restarted $(unit_show NRestarts) times"; return 1; }
    journal_has 'source auto: no camera found; waiting' || { echo "no wait for a camera logged"; return 1; }
    journal_has 'display auto: no connected screen' || { echo "no wait for a panel logged"; return 1; }
    local expect='^display: '
    console_round 60 status || return 1
    grep -q '^source: auto (no camera yet' "$CONSOLE" || { echo "status: $(grep -a '^source' "$CONSOLE")"; return 1; }
    sleep "$(scaled 10)"
    local pngs
    pngs=$(find /var/lib/mirror -name '*.png' | wc -l)
    ((pngs == 0)) || { echo "$pngs PNG files written into /var/lib/mirror unasked"; return 1; }
}

# vimc and vkms loaded: the same process (no restart) rebuilds on the camera and the panel.
check_devices_plugged_in() {
    modprobe vimc && modprobe vkms || { echo "cannot load vimc, vkms"; return 1; }
    udevadm settle --timeout="$(scaled 30)"
    log "vimc and vkms loaded"
    local t0=$SECONDS
    wait_for 150 journal_has 'connected: rebuilding the pipeline' ||
        { echo "no rebuild: $(journalctl -q -o cat -u mirror.service | tail -3 | tr '\n' ' ')"; return 1; }
    local expect='^display: drm' try
    for try in 1 2 3; do
        console_round 60 status || return 1
        grep -q '^display: drm' "$CONSOLE" && grep -q '^source: .*libcamera' "$CONSOLE" && break
        ((try < 3)) || { echo "status: $(grep -a '^source\|^display' "$CONSOLE" | tr '\n' ' ')"; return 1; }
        sleep "$(scaled 20)"
    done
    log "on the camera and the panel $((SECONDS - t0)) s after the modules"
    [ "$(unit_show NRestarts)" = 0 ] || { echo "the process restarted ($(unit_show NRestarts))"; return 1; }
    journalctl --no-pager -u mirror.service >"$R/service-journal.txt" 2>&1
}

# rss_kb PID: resident memory of a process.
rss_kb() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status" 2>/dev/null; }

# HIL_SOAK_MINUTES cycles: the camera unplugged (vimc.0 unbound) for a while and plugged in again,
# one cycle per HIL_SOAK_PERIOD_S at the least (longer when the service needs it to come back);
# the service's memory before each unplug goes to soak.txt. It must end active, and the memory
# of the last cycles may not exceed the first's by more than 20 %.
check_replug_soak() {
    local drv=/sys/bus/platform/drivers/vimc i pid rss t0 first="" last=""
    echo "cycle seconds pid rss_kb restarts" >"$R/soak.txt"
    for ((i = 1; i <= HIL_SOAK_MINUTES; i++)); do
        t0=$SECONDS
        wait_for 150 bash -c '[ "$(systemctl is-active mirror.service)" = active ]' || { echo "cycle $i: not active"; return 1; }
        pid=$(unit_show MainPID)
        rss=$(rss_kb "$pid")
        echo "$i $SECONDS $pid $rss $(unit_show NRestarts)" >>"$R/soak.txt"
        echo "HIL FIGURE soak cycle=$i pid=$pid rss_kb=$rss restarts=$(unit_show NRestarts)" >/dev/console 2>/dev/null || true
        [ -n "$first" ] || first=$rss
        last=$rss
        echo vimc.0 >"$drv/unbind" || { echo "cycle $i: cannot unbind"; return 1; }
        sleep $((HIL_SOAK_PERIOD_S / 2))
        echo vimc.0 >"$drv/bind" || { echo "cycle $i: cannot bind"; return 1; }
        udevadm settle --timeout="$(scaled 30)"
        while ((SECONDS - t0 < HIL_SOAK_PERIOD_S)); do sleep 1; done
    done
    wait_for 150 bash -c '[ "$(systemctl is-active mirror.service)" = active ]' || { echo "not active at the end"; return 1; }
    ((last <= first * 12 / 10)) || { echo "memory grew: $first kB -> $last kB"; return 1; }
}

# --- calibration --------------------------------------------------------------------------------

# The guest's time to start the mirror and show three small frames of its synthetic scene
# (headless): the libraries read over 9p, the cascade loaded, llvmpipe's shaders compiled, all
# under TCG; the service's own start-up later finds the page cache warm. Against the reference
# machine's time (HIL_CALIBRATION_REF_MS) it gives HIL_SCALE_PCT, printed for the host, which
# stretches its overall limit the same way.
calibrate() {
    local t0 ms rc=0 out=$R/calibration
    t0=$(now_ms)
    timeout 600 "$HIL_BIN/mirror" --source synthetic --display "headless:$out" --frames 3 \
        --set source.width=160 --set source.height=120 --set display.width=160 \
        --set display.height=120 --set console.stdin=false --set buttons.enabled=false \
        --set "state.dir=\"/tmp/hil-calibration\"" >"$R/calibration.log" 2>&1 </dev/null || rc=$?
    ms=$(($(now_ms) - t0))
    local ref=${HIL_CALIBRATION_REF_MS:?set by run-hil.sh}
    local max=${HIL_SCALE_MAX_PCT:?set by run-hil.sh}
    HIL_SCALE_PCT=$((ms * 100 / ref))
    ((HIL_SCALE_PCT >= 100)) || HIL_SCALE_PCT=100
    ((HIL_SCALE_PCT <= max)) || HIL_SCALE_PCT=$max
    log "calibration: the mirror started in $ms ms (exit $rc), reference $ref ms: deadlines x$HIL_SCALE_PCT%"
    echo "HIL CALIBRATION start_ms=$ms ref_ms=$ref scale_pct=$HIL_SCALE_PCT exit=$rc"
}

log "guest up, kernel $KVER, PID 1 $(cat /proc/1/comm)"
calibrate
for c in $HIL_CHECKS; do
    run_check "$c"
done
log "guest done"
