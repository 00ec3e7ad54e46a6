# SPDX-License-Identifier: GPL-3.0-or-later
# shockgas_source_hash(<hash_var> <listing_var> SOURCE_DIR DIRECTORIES COMPILER_INFO):
# SHA-256 over COMPILER_INFO and every file under DIRECTORIES (a CMake list of
# directories and single files), each file's own SHA-256 and path relative to
# SOURCE_DIR, sorted. Hidden files and editors' leftovers (.name, name~, *.orig,
# *.rej, *.swp) are not sources: an editor's swap file beside checkpoint.cpp
# would otherwise make every run in progress another simulator's. Used at build
# time (cmake -P) by SourceStamp.cmake, which the figure pipeline's simulations
# depend on, and by BuildInfo.cmake, which compiles the same hash into the
# programs as simulator_sha256: one computation, so the stamp that decides
# whether a simulation is stale and the hash that decides whether a checkpoint
# can be continued are the same value. (Globbing here is deliberate: the hash
# must cover every file in these directories, including ones added later.)
function(shockgas_source_hash hash_var listing_var source_dir directories compiler_info)
  set(content "${compiler_info}\n")
  foreach(dir IN LISTS directories)
    if(IS_DIRECTORY "${dir}")
      file(GLOB_RECURSE files LIST_DIRECTORIES false "${dir}/*")
    elseif(EXISTS "${dir}")
      set(files "${dir}")
    else()
      message(FATAL_ERROR "shockgas_source_hash: no directory or file '${dir}'")
    endif()
    list(FILTER files EXCLUDE REGEX "/\\.[^/]*$|~$|\\.(orig|rej|swp|swo)$")
    list(SORT files)
    foreach(f IN LISTS files)
      file(SHA256 "${f}" hash)
      file(RELATIVE_PATH relative "${source_dir}" "${f}")
      string(APPEND content "${hash}  ${relative}\n")
    endforeach()
  endforeach()
  string(SHA256 stamp "${content}")
  set(${hash_var} "${stamp}" PARENT_SCOPE)
  set(${listing_var} "${content}" PARENT_SCOPE)
endfunction()
