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

run_check() {
    local name=$1 why
    log "check $name"
    if why=$("check_$name" 2>&1); then
        echo "HIL PASS $name" | tee -a "$R/checks.txt"
    else
        why=$(printf '%s' "$why" | tr '\n' ' ' | cut -c1-300)
        echo "HIL FAIL $name: ${why:-failed}" | tee -a "$R/checks.txt"
    fi
}

# wait_for SECONDS COMMAND...: poll until COMMAND succeeds; false on timeout.
wait_for() {
    local deadline=$((SECONDS + $1))
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
        udevadm settle --timeout=60 || { echo "udevadm settle timed out"; return 1; }
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
    timeout 60 cam -c 1 -C3 -F"$R/cam-frame-#.bin" >"$R/cam-capture.txt" 2>&1 ||
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

# --- the firmware -----------------------------------------------------------------------------

check_mirror_headless() {
    local out=$R/mirror-headless
    rm -rf "$out"
    # Small frames: llvmpipe under TCG renders ~70x slower than on the host.
    timeout 120 "$HIL_BIN/mirror" --source synthetic --display "headless:$out" --frames 10 \
        --set source.width=320 --set source.height=240 --set display.width=320 \
        --set display.height=240 --set display.snapshot_every=5 \
        --set console.stdin=false --set "state.dir=\"$R/state\"" \
        >"$R/mirror-headless.log" 2>&1 </dev/null ||
        { echo "mirror exited $?: $(tail -3 "$R/mirror-headless.log")"; return 1; }
    ls "$out"/*.png >/dev/null 2>&1 || { echo "no snapshot in $out"; return 1; }
}

# The mirror's own console on ttyS1 (the service's drop-in sets console.serial): the host types
# `status` and `selftest`; every selftest line must PASS.
check_console_selftest() {
    # selftest asks for recent frames: wait for READY=1 (the unit turns active after the first
    # frame is shown), which under TCG comes ~60 s after the postinst started it.
    wait_for 150 bash -c '[ "$(systemctl is-active mirror.service)" = active ]' ||
        { echo "mirror.service not active: $(systemctl is-active mirror.service)"; return 1; }
    rm -f "$R"/console.*
    printf 'status\nselftest\n' >"$R/console.send"
    echo 'selftest: ' >"$R/console.expect"
    touch "$R/console.ready"
    wait_for 90 test -e "$R/console.done" || { echo "host never finished"; return 1; }
    local t=$R/console.txt
    grep -aq 'selftest: all PASS' "$t" ||
        { echo "selftest did not pass: $(tr -d '\r' <"$t" | grep -a 'FAIL\|selftest\|error' | head -5 | tr '\n' ' ')"; return 1; }
    grep -aq 'error:' "$t" && { echo "the console answered an error: $(grep -a 'error:' "$t" | head -2)"; return 1; }
    return 0
}

# --- the Debian package and the service ----------------------------------------------------

# dpkg -i into the tmpfs overlay root, as on a clean machine: files, conffile, the user, the unit.
check_package_installed() {
    [ -f "${HIL_PACKAGE:-}" ] || { echo "no package (HIL_PACKAGE=${HIL_PACKAGE:-})"; return 1; }
    # The test decides when the mirror starts (the postinst starts it under systemd), and on what:
    # the synthetic scene on the headless display, snapshots in the state directory.
    mkdir -p /etc/systemd/system/mirror.service.d
    local watchdog=60
    [ -z "${HIL_SERVICE_TYPE:-}" ] || watchdog=0  # a unit checked without READY/WATCHDOG support
    cat >/etc/systemd/system/mirror.service.d/hil.conf <<UNIT
[Service]
# Under TCG start-up (libraries over 9p, llvmpipe) takes ~50 s and frames are ~70x slower.
TimeoutStartSec=150
WatchdogSec=$watchdog
${HIL_SERVICE_TYPE:+Type=$HIL_SERVICE_TYPE}
ExecStart=
ExecStart=/usr/bin/mirror --config /etc/mirror/mirror.toml --source synthetic --display headless:/var/lib/mirror/snapshots --set source.width=320 --set source.height=240 --set display.width=320 --set display.height=240 --set display.snapshot_every=5 --set console.stdin=false --set 'console.serial="/dev/ttyS1"' --set buttons.enabled=false
UNIT
    # Installed as on a machine without this user, these files, or the unit enabled. dpkg's
    # database is the host's installed-package list (dependencies are checked against it) without
    # the per-package file lists: reading those thousands of files over 9p takes ~2 min under TCG.
    local admin=/var/lib/dpkg-hil
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
    local g
    for g in video render gpio dialout; do
        id -nG mirror | grep -qw "$g" || { echo "user mirror not in group $g"; return 1; }
    done
    [ "$(systemctl is-enabled mirror.service 2>&1)" = enabled ] || { echo "mirror.service not enabled"; return 1; }
}

# systemctl start returns once the unit sent READY=1 (Type=notify): the first frame is shown.
# Then the unit's sandbox must let it run: snapshots written as user mirror in its StateDirectory.
check_service_ready() {
    [ "$(cat /proc/1/comm)" = systemd ] || { echo "PID 1 is not systemd (HIL_SYSTEMD=0)"; return 1; }
    local rc=0 why=""
    log "systemctl start mirror"
    timeout 100 systemctl start mirror.service >"$R/service-start.txt" 2>&1 || rc=$?
    if ((rc != 0)); then
        why="systemctl start failed ($rc)"
    elif ! wait_for 90 bash -c 'journalctl --no-pager -u mirror.service >"$0/service-journal.txt" 2>&1; ls /var/lib/mirror/snapshots/*.png' "$R"; then
        why="no snapshot in /var/lib/mirror/snapshots"
    else
        local png
        png=$(ls /var/lib/mirror/snapshots/*.png | head -1)
        [ "$(stat -c %U "$png")" = mirror ] || why="$png is not owned by user mirror"
    fi
    systemctl status --no-pager -n 0 mirror.service >"$R/service-status.txt" 2>&1
    journalctl --no-pager -u mirror.service >"$R/service-journal.txt" 2>&1
    if [ -n "$why" ]; then
        echo "$why: $(systemctl show -p ActiveState,SubState,Result,NRestarts mirror.service | tr '\n' ' ')"
        return 1
    fi
    systemctl stop mirror.service || { echo "systemctl stop failed"; return 1; }
}

log "guest up, kernel $KVER, PID 1 $(cat /proc/1/comm)"
for c in $HIL_CHECKS; do
    run_check "$c"
done
log "guest done"
