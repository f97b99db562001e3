#!/usr/bin/env bash
# make-initramfs.sh OUT.cpio.gz: the busybox-static initramfs of the emulated machine: busybox,
# scripts/hil/initramfs-init as /init, and the installed kernel's virtio, 9p and overlay modules
# with their dependencies, in load order. Rebuilt only when missing or older than its inputs.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"

[ $# -eq 1 ] || { echo "usage: $0 OUT.cpio.gz" >&2; exit 2; }
hil_find_kernel
out=$1
if [ -f "$out" ] && [ "$out" -nt "$here/initramfs-init" ] && [ "$out" -nt "$0" ] &&
    [ "$out" -nt "/lib/modules/$HIL_KVER/modules.dep" ]; then
    exit 0
fi
busybox=$(command -v busybox) || hil_skip "busybox missing (apt-get install busybox-static)"
file -L "$busybox" 2>/dev/null | grep -q 'statically linked' || [ -x /bin/busybox ] ||
    hil_skip "busybox is not static (apt-get install busybox-static)"
[ -x /bin/busybox ] && busybox=/bin/busybox

moddir=/lib/modules/$HIL_KVER
wanted=(virtio_pci 9pnet_virtio 9p overlay)
declare -A loaded=()
order=()
# add MODULE_PATH: its dependencies first (modules.dep lists them last-needed first), then itself.
add() {
    local path=$1 deps i
    [ -z "${loaded[$path]:-}" ] || return 0
    deps=$(grep -m1 "^$path:" "$moddir/modules.dep" | cut -d: -f2)
    read -ra deps <<<"$deps"
    for ((i = ${#deps[@]} - 1; i >= 0; i--)); do add "${deps[$i]}"; done
    loaded[$path]=1
    order+=("$path")
}
for m in "${wanted[@]}"; do
    path=$(grep -m1 -E "/$m\.ko(\.[a-z]+)?:" "$moddir/modules.dep" | cut -d: -f1) ||
        hil_skip "module $m not in $moddir (kernel without virtio/9p/overlay modules?)"
    case "$path" in *.ko) ;; *) hil_skip "compressed module $path: not supported by busybox insmod here" ;; esac
    add "$path"
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/bin" "$tmp/modules"
cp "$busybox" "$tmp/bin/busybox"
cp "$here/initramfs-init" "$tmp/init"
chmod 755 "$tmp/init"
: >"$tmp/modules.order"
for p in "${order[@]}"; do
    cp "$moddir/$p" "$tmp/modules/"
    basename "$p" >>"$tmp/modules.order"
done
mkdir -p "$(dirname "$out")"
(cd "$tmp" && find . | "$busybox" cpio -o -H newc 2>/dev/null | gzip -1) >"$out.tmp"
mv "$out.tmp" "$out"
hil_say "initramfs $out: busybox + ${#order[@]} modules ($(basename -a "${order[@]}" | tr '\n' ' '))"
