# shellcheck shell=bash
# Shared by the HIL scripts (sourced, not run). Finds the kernel the emulated machine boots and
# the packages it needs; every version is read from the system, never written down here.

hil_say() { printf 'hil: %s\n' "$*" >&2; }

# Exit code that ctest's SKIP_RETURN_CODE maps to "skipped".
HIL_SKIP=77

# hil_skip REASON: the test cannot run on this machine (missing packages), say why, exit 77.
hil_skip() {
    printf 'HIL SKIP: %s\n' "$*" >&2
    exit "$HIL_SKIP"
}

# Sets HIL_KVER (e.g. 6.1.0-56-amd64), HIL_VMLINUZ, HIL_HEADERS, HIL_SOURCE_TARBALL and
# HIL_SOURCE_TOP (the directory name inside the tarball), or skips with the reason.
# The kernel is the newest installed linux-image that also has its linux-headers, so the
# out-of-tree modules match it exactly (vermagic and symbol versions).
hil_find_kernel() {
    local v candidates=()
    for v in /boot/vmlinuz-*; do
        [ -e "$v" ] || continue
        candidates+=("${v#/boot/vmlinuz-}")
    done
    ((${#candidates[@]})) || hil_skip "no kernel image in /boot (apt-get install linux-image-amd64)"
    HIL_KVER=
    while read -r v; do
        if [ -f "/usr/src/linux-headers-$v/Module.symvers" ] && [ -d "/lib/modules/$v/kernel" ]; then
            HIL_KVER=$v
        fi
    done < <(printf '%s\n' "${candidates[@]}" | sort -V)
    [ -n "$HIL_KVER" ] || hil_skip "no linux-headers for the installed kernel(s) ${candidates[*]}" \
        "(apt-get install linux-headers-amd64)"
    HIL_VMLINUZ=/boot/vmlinuz-$HIL_KVER
    [ -r "$HIL_VMLINUZ" ] || hil_skip "$HIL_VMLINUZ is not readable"
    # shellcheck disable=SC2034 # used by the scripts that source this file
    HIL_HEADERS=/usr/src/linux-headers-$HIL_KVER
    # 6.1.0-56-amd64 -> linux-source-6.1
    local series
    series=$(printf '%s' "$HIL_KVER" | sed -E 's/^([0-9]+\.[0-9]+).*/\1/')
    HIL_SOURCE_TOP=linux-source-$series
    HIL_SOURCE_TARBALL=/usr/src/$HIL_SOURCE_TOP.tar.xz
    [ -r "$HIL_SOURCE_TARBALL" ] || hil_skip "$HIL_SOURCE_TARBALL missing (apt-get install linux-source-$series)"
}

# hil_require_tools TOOL...: skip unless every tool is on PATH.
hil_require_tools() {
    local t missing=()
    for t in "$@"; do
        command -v "$t" >/dev/null 2>&1 || missing+=("$t")
    done
    ((${#missing[@]} == 0)) || hil_skip "missing tools: ${missing[*]}" \
        "(apt-get install qemu-system-x86 busybox-static kmod udev libcamera-tools libcamera-ipa gpiod)"
}
