#!/usr/bin/env bash
# The package's maintainer scripts (cmake/debian) keep debhelper's promises about the unit, run
# against a scratch root (DPKG_ROOT, which deb-systemd-helper honours) with the commands that would
# touch this machine (user and group tools, udevadm, systemctl, deb-systemd-invoke) replaced by
# stubs that only log:
#   - a first install enables mirror.service and puts the user mirror in its groups;
#   - an admin's disable survives an upgrade (postinst configure OLD-VERSION) and a reconfigure;
#   - remove masks the unit, a reinstall unmasks it, purge forgets its state and /var/lib/mirror.
# Usage: maintainer_scripts.sh SCRIPTS_DIR UNIT_DIR
set -euo pipefail
scripts=$1
units=$2
command -v deb-systemd-helper >/dev/null || { echo "SKIP: deb-systemd-helper missing"; exit 77; }

root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root/stubs" "$root/lib/systemd/system" "$root/etc/systemd/system" "$root/var/lib/mirror"
cp "$units/mirror.service" "$units/mirror-console.service" "$root/lib/systemd/system/"
for tool in groupadd useradd usermod getent udevadm systemctl deb-systemd-invoke; do
    printf '#!/bin/sh\necho "%s $*" >>"%s/calls.log"\n' "$tool" "$root" >"$root/stubs/$tool"
    chmod +x "$root/stubs/$tool"
done
# What dpkg sets for a maintainer script (deb-systemd-helper refuses to run without it).
export DPKG_ROOT=$root PATH="$root/stubs:$PATH" DPKG_MAINTSCRIPT_PACKAGE=mirror

link=$root/etc/systemd/system/multi-user.target.wants/mirror.service
mask=$root/etc/systemd/system/mirror.service
fail() { echo "FAIL: $*"; exit 1; }
run() { DPKG_MAINTSCRIPT_NAME=$1 sh -e "$scripts/$1" "${@:2}" || fail "$* exited $?"; }

run postinst configure
[ -L "$link" ] || fail "a first install did not enable mirror.service"
# The devices' groups, and the journal's: the console's bug report reads the unit's journal.
grep -qx 'usermod --append --groups video,render,gpio,dialout,systemd-journal mirror' \
    "$root/calls.log" || fail "the user mirror is not put in its groups: $(grep usermod "$root/calls.log")"
echo "first install: enabled, user mirror in video, render, gpio, dialout, systemd-journal"

rm "$link"  # what `systemctl disable mirror.service` does
run postinst configure 0.9.0
[ ! -e "$link" ] || fail "an upgrade re-enabled the unit the admin disabled"
run postinst configure 0.9.0
[ ! -e "$link" ] || fail "a reconfigure re-enabled the unit the admin disabled"
echo "disabled by the admin: stays disabled across upgrade and reconfigure"

run prerm remove
run postrm remove
[ -L "$mask" ] && [ "$(readlink "$mask")" = /dev/null ] || fail "remove did not mask the unit"
[ -d "$root/var/lib/mirror" ] || fail "remove deleted what the mirror learnt (only purge may)"
run postinst configure 0.9.0
[ ! -e "$mask" ] || fail "a reinstall left the unit masked"
echo "remove: masked, state kept; reinstall: unmasked"

run prerm remove
run postrm remove
run postrm purge
[ ! -e "$mask" ] || fail "purge left the unit masked"
[ ! -d "$root/var/lib/mirror" ] || fail "purge kept /var/lib/mirror"
[ -z "$(ls -A "$root/var/lib/systemd/deb-systemd-helper-enabled" 2>/dev/null)" ] ||
    fail "purge kept the unit's enable state"
run postinst configure
[ -L "$link" ] || fail "an install after purge did not enable the unit"
echo "purge: state forgotten; install after purge: enabled"
echo "maintainer scripts: ok"
