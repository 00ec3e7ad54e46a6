# SPDX-License-Identifier: GPL-3.0-or-later
# Find a Python 3 interpreter that can import numpy, scipy and h5py. Debian's
# python3-numpy & co. install into /usr/bin/python3, which need not be the
# python3 first on PATH (pyenv, conda, venvs), so each candidate is asked.
set(_shockgas_python_candidates)
if(SHOCKGAS_PYTHON)
  list(APPEND _shockgas_python_candidates "${SHOCKGAS_PYTHON}")
endif()
find_program(_shockgas_path_python NAMES python3 NO_CACHE)
list(APPEND _shockgas_python_candidates /usr/bin/python3 "${_shockgas_path_python}")
unset(_shockgas_found_python)
foreach(candidate IN LISTS _shockgas_python_candidates)
  if(candidate AND EXISTS "${candidate}")
    execute_process(COMMAND "${candidate}" -c "import numpy, scipy, h5py"
                    RESULT_VARIABLE _import_result OUTPUT_QUIET ERROR_QUIET)
    if(_import_result EQUAL 0)
      set(_shockgas_found_python "${candidate}")
      break()
    endif()
  endif()
endforeach()
if(_shockgas_found_python)
  set(SHOCKGAS_PYTHON "${_shockgas_found_python}" CACHE FILEPATH "Python 3 with numpy, scipy and h5py" FORCE)
  message(STATUS "shockgas: Python with numpy/scipy/h5py: ${SHOCKGAS_PYTHON}")
else()
  set(SHOCKGAS_PYTHON "" CACHE FILEPATH "Python 3 with numpy, scipy and h5py" FORCE)
  message(WARNING "shockgas: no python3 can import numpy, scipy and h5py; Python cross-checks are skipped. "
                  "Run tools/install-deps.sh.")
endif()
