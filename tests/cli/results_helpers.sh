# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the analysis tests that read results files back (needs $dump, shockgas-dump, and fail()).
# has FILE GROUP LINE-REGEX: the group's attributes (shockgas-dump gnuplot-vars) include a line matching.
has() {
  "$dump" gnuplot-vars "$1" "$2" --prefix v | grep -Eq -- "$3" || fail "$1 $2 has no line /$3/:
$("$dump" gnuplot-vars "$1" "$2" --prefix v)"
  echo "ok: $1 $2: /$3/"
}
# lacks FILE GROUP LINE-REGEX: no line matches.
lacks() {
  "$dump" gnuplot-vars "$1" "$2" --prefix v | grep -Eq -- "$3" && fail "$1 $2 has a line /$3/"
  echo "ok: $1 $2: no /$3/"
}
