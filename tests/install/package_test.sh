#!/usr/bin/env bash
# package_test.sh BUILD_DIR CPACK (label install; docs/install.md)
# `cpack -G DEB` must write the two Debian packages, with their dependencies
# declared (the libraries' packages, found by dpkg-shlibdeps, and those named in
# cmake/Packaging.cmake) and the files each must hold; the packaged program must run.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
build=$(cd "$1" && pwd) cpack=$2
fail() { echo "FAIL: $*"; exit 1; }
for tool in dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" >/dev/null || fail "$tool not found: run tools/install-deps.sh (Debian packages dpkg, dpkg-dev)"
done

work=$(mktemp -d "${TMPDIR:-/tmp}/shockgas-package-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
(cd "$work" && "$cpack" -G DEB --config "$build/CPackConfig.cmake" -B "$work" >cpack.log 2>&1) \
  || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
runtime=$(ls "$work"/shockgas_*.deb) dev=$(ls "$work"/shockgas-dev_*.deb) \
  || fail "cpack wrote $(ls "$work"/*.deb 2>/dev/null), not shockgas_*.deb and shockgas-dev_*.deb"

# Each expected entry must be a line of `dpkg-deb --contents` / a dependency of `dpkg-deb --info`.
expect_depends() {
  local deb=$1; shift
  local depends
  depends=$(dpkg-deb --field "$deb" Depends)
  for needed in "$@"; do
    grep -Eq "(^|, )$needed( |,|$)" <<<"$depends" || fail "$(basename "$deb") does not depend on $needed: $depends"
  done
}
expect_files() {
  local deb=$1; shift
  local contents
  contents=$(dpkg-deb --contents "$deb" | awk '{print $NF}')
  for needed in "$@"; do
    grep -Eq "^\./$needed$" <<<"$contents" || fail "$(basename "$deb") lacks $needed"
  done
}

dpkg-deb --info "$runtime"
expect_depends "$runtime" 'libhdf5-[0-9a-z.-]+' 'libgsl[0-9]+' 'libfmt[0-9]+' 'libstdc\+\+6' python3 python3-numpy python3-h5py
expect_files "$runtime" \
  usr/bin/shockgas-sim usr/bin/shockgas-merge usr/bin/shockgas-dump usr/bin/shockgas-burgers usr/bin/shockgas-analyze \
  usr/bin/shockgas-plan usr/share/man/man1/shockgas-plan.1.gz \
  usr/share/man/man1/shockgas-sim.1.gz usr/share/man/man1/shockgas-merge.1.gz usr/share/man/man1/shockgas-dump.1.gz \
  usr/share/man/man1/shockgas-burgers.1.gz usr/share/man/man1/shockgas-analyze.1.gz \
  usr/lib/python3/dist-packages/shockgas/__init__.py usr/share/shockgas/CMakeLists.txt \
  usr/share/shockgas/paper_targets/fig1.paper.json usr/share/shockgas/figures/style.gp \
  usr/share/doc/shockgas/README.md usr/share/doc/shockgas/LICENSE usr/share/doc/shockgas/copyright \
  'usr/lib/(.*/)?cmake/shockgas/shockgasPrograms.cmake'

dpkg-deb --info "$dev" | grep -E "Package|Depends"
version=$(dpkg-deb --field "$runtime" Version)
expect_depends "$dev" "shockgas \(= ${version//./\\.}\)" libhdf5-dev libgsl-dev libfmt-dev
expect_files "$dev" usr/include/shockgas/engines/engine.hpp usr/include/shockgas/analysis/fit.hpp \
  usr/share/doc/shockgas-dev/LICENSE usr/share/doc/shockgas-dev/copyright \
  'usr/lib/(.*/)?libshockgas_run\.a' 'usr/lib/(.*/)?libshockgas_engines\.a' 'usr/lib/(.*/)?libshockgas_analysis\.a' \
  'usr/lib/(.*/)?cmake/shockgas/shockgasConfig\.cmake' 'usr/lib/(.*/)?cmake/shockgas/shockgasTargets\.cmake'

# The engines' internals stay private: the public interface is shockgas/engines/engine.hpp.
if dpkg-deb --contents "$dev" | grep -Eq 'include/shockgas/.*(event_engine|passthrough_engine|quaternary_heap)\.hpp'; then
  fail "$(basename "$dev") installs an engine's private header"
fi

# The packaged (stripped) program runs, and its man page documents it.
dpkg-deb -x "$runtime" "$work/root"
"$work/root/usr/bin/shockgas-sim" --version | grep -q "^shockgas-sim " || fail "the packaged shockgas-sim does not run"
gzip -dc "$work/root/usr/share/man/man1/shockgas-sim.1.gz" | grep -q -- "restitution" \
  || fail "the packaged man page lacks shockgas-sim's options"
echo "ok: $(basename "$runtime") and $(basename "$dev")"
