# Run at build time (cmake -P). Writes STAMP = SHA-256 over the simulator's
# sources and the compiler and flags, rewriting the file only when that hash
# changes. Simulations depend on this stamp instead of on the shockgas-sim
# binary: the binary is relinked at every commit (it embeds git describe for
# provenance), but a simulation is stale only when the code that computes it,
# or the way it is compiled, changed. (Globbing here is deliberate: the stamp
# must cover every file in these directories, including ones added later.)
#
# DIRECTORIES is separated by "|", not ";": a ";" inside a -D value reaches
# this script escaped ("\;"), which makes the whole value one directory that
# does not exist, and the stamp then hashed no file at all (so until this was
# found, changing the simulator never reran a simulation). STAMP.files lists
# what was hashed; ctest pipeline.stamp_covers_sim_sources checks it.
string(REPLACE "|" ";" _directories "${DIRECTORIES}")
set(_content "${COMPILER_INFO}\n")
foreach(dir IN LISTS _directories)
  if(NOT IS_DIRECTORY "${dir}")
    message(FATAL_ERROR "SourceStamp: no directory '${dir}'")
  endif()
  file(GLOB_RECURSE _files LIST_DIRECTORIES false "${dir}/*")
  list(SORT _files)
  foreach(f IN LISTS _files)
    file(SHA256 "${f}" _hash)
    file(RELATIVE_PATH _relative "${SOURCE_DIR}" "${f}")
    string(APPEND _content "${_hash}  ${_relative}\n")
  endforeach()
endforeach()
string(SHA256 _stamp "${_content}")
set(_old "")
if(EXISTS "${STAMP}")
  file(READ "${STAMP}" _old)
endif()
if(NOT _old STREQUAL "${_stamp}")
  file(WRITE "${STAMP}" "${_stamp}")
endif()
if(NOT _old STREQUAL "${_stamp}" OR NOT EXISTS "${STAMP}.files")
  file(WRITE "${STAMP}.files" "${_content}")
endif()
