# SPDX-License-Identifier: GPL-3.0-or-later
# CMake reads a JSON number as 17 significant digits (restitution 0.9 comes
# back as 0.90000000000000002), which then shows in every command and build
# log. This gives the shortest decimal that CMake's own JSON reader turns back
# into the same 17 digits, i.e. the same double: the number as it was written
# (shortest round-trip formatting). Anything else (integers, exponents, text)
# is passed through unchanged.
function(_shockgas_shortest_number value out)
  set(${out} "${value}" PARENT_SCOPE)
  if(NOT value MATCHES "^(-?)([0-9]+)\\.([0-9]+)$")
    return()
  endif()
  set(sign "${CMAKE_MATCH_1}")
  set(whole "${CMAKE_MATCH_2}")
  set(fraction "${CMAKE_MATCH_3}")
  string(LENGTH "${fraction}" digits)
  if(digits LESS 2 OR whole GREATER 999999999999)
    return()
  endif()
  math(EXPR last "${digits} - 1")
  if(last GREATER 17)  # 1 followed by 18 digits is the most math(EXPR) holds (64-bit)
    set(last 17)
  endif()
  foreach(n RANGE 1 ${last})
    string(SUBSTRING "${fraction}" 0 ${n} head)
    # The fraction cut to n digits, and the same rounded up (with the carry).
    math(EXPR up "1${head} + 1")  # a leading 1 keeps the zeros and shows the carry
    string(SUBSTRING "${up}" 1 -1 up_fraction)
    set(up_whole ${whole})
    if(up MATCHES "^2")
      math(EXPR up_whole "${whole} + 1")
    endif()
    foreach(candidate "${sign}${whole}.${head}" "${sign}${up_whole}.${up_fraction}")
      string(JSON back GET "[${candidate}]" 0)
      if(back STREQUAL value)
        string(REGEX REPLACE "0+$" "" candidate "${candidate}")
        string(REGEX REPLACE "\\.$" "" candidate "${candidate}")
        set(${out} "${candidate}" PARENT_SCOPE)
        return()
      endif()
    endforeach()
  endforeach()
endfunction()
