#!/usr/bin/env bash
# build-modules.sh OUTDIR: builds vimc (camera), vkms (display) and gpio-sim (GPIO) out of tree
# from Debian's linux-source tarball against the linux-headers of the installed kernel image,
# which does not enable them. Results are cached in OUTDIR and rebuilt only when missing:
#   OUTDIR/KVER/extra/{vimc,vkms,gpio-sim}.ko
#   OUTDIR/KVER/root/lib/modules/KVER/modules.*   (depmod -b output for the whole tree + extra)
# Prints the directory OUTDIR/KVER on success. Exit 77 when the kernel packages are missing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"

[ $# -eq 1 ] || { echo "usage: $0 OUTDIR" >&2; exit 2; }
hil_find_kernel
hil_require_tools make gcc depmod tar xz

out=$(mkdir -p "$1" && cd "$1" && pwd)/$HIL_KVER
extra=$out/extra
stage=$out/root/lib/modules/$HIL_KVER
modules=(vimc vkms gpio-sim)

have_all() {
    local m
    for m in "${modules[@]}"; do [ -f "$extra/$m.ko" ] || return 1; done
    [ -f "$stage/modules.dep.bin" ]
}
if have_all; then
    echo "$out"
    exit 0
fi

src=$out/src
rm -rf "${src:?}" "${out:?}/root"
mkdir -p "$src" "$extra" "$stage"
top=$HIL_SOURCE_TOP
hil_say "extracting vimc, vkms, gpio-sim and irq_sim from $HIL_SOURCE_TARBALL"
tar -xJf "$HIL_SOURCE_TARBALL" -C "$src" --wildcards \
    "$top/drivers/media/test-drivers/vimc/*" "$top/drivers/gpu/drm/vkms/*" \
    "$top/drivers/gpio/gpio-sim.c" "$top/drivers/gpio/gpiolib.h" "$top/kernel/irq/irq_sim.c"

# vimc and vkms: their own Makefile, with the config symbol Debian leaves unset forced to m.
mkdir -p "$src/vimc" "$src/vkms" "$src/gpio-sim"
cp "$src/$top"/drivers/media/test-drivers/vimc/*.[ch] "$src/vimc/"
sed 's/obj-$(CONFIG_VIDEO_VIMC)/obj-m/' "$src/$top/drivers/media/test-drivers/vimc/Makefile" \
    >"$src/vimc/Kbuild"
cp "$src/$top"/drivers/gpu/drm/vkms/*.[ch] "$src/vkms/"
sed 's/obj-$(CONFIG_DRM_VKMS)/obj-m/' "$src/$top/drivers/gpu/drm/vkms/Makefile" >"$src/vkms/Kbuild"

# gpio-sim needs the interrupt simulator, which Debian builds neither in nor as a module
# (CONFIG_IRQ_SIM off): compile kernel/irq/irq_sim.c into the gpio-sim module itself. Its
# exports would clash with nothing but are not needed, and irq_to_desc() is not exported to
# modules, so the one call through it becomes the exported equivalent.
cp "$src/$top/drivers/gpio/gpio-sim.c" "$src/gpio-sim/gpio-sim-main.c"
cp "$src/$top/drivers/gpio/gpiolib.h" "$src/gpio-sim/"
sed -e '/^EXPORT_SYMBOL/d' \
    -e 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' \
    "$src/$top/kernel/irq/irq_sim.c" >"$src/gpio-sim/irq_sim.c"
grep -q 'generic_handle_irq(irqnum)' "$src/gpio-sim/irq_sim.c" ||
    { hil_say "irq_sim.c changed upstream: the irq_to_desc workaround no longer applies"; exit 1; }
printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' >"$src/gpio-sim/Kbuild"

for m in "${modules[@]}"; do
    hil_say "building $m.ko for $HIL_KVER"
    make -s -C "$HIL_HEADERS" M="$src/$m" -j"$(nproc)" modules >"$src/$m.log" 2>&1 ||
        { cat "$src/$m.log" >&2; hil_say "building $m failed"; exit 1; }
    cp "$src/$m/$m.ko" "$extra/"
done

# depmod in the guest takes ~90 s under emulation: index the installed tree plus extra/ here.
# The stage holds symlinks to the installed modules; only the index files are used later.
ln -s "/lib/modules/$HIL_KVER/kernel" "$stage/kernel"
ln -s "$extra" "$stage/extra"
cp /lib/modules/"$HIL_KVER"/modules.{order,builtin,builtin.modinfo} "$stage/"
depmod -b "$out/root" "$HIL_KVER"
grep -q '^extra/vimc.ko:' "$stage/modules.dep" ||
    { hil_say "depmod did not index extra/ (symlinked tree not followed?)"; exit 1; }
rm -rf "${src:?}/${top:?}"
echo "$out"
