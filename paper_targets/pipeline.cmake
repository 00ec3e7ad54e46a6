# SPDX-License-Identifier: GPL-3.0-or-later
# The figure pipeline's building blocks. A figure's runs are read from
# paper_targets/<figure>.<fidelity>.json:
#   {"runs": [{"name": "r0.9", "label": "r = 0.9", "parts": 1,
#              "options": {"particles": 20000, "restitution": 0.9, ...}}, ...]}
# "label" describes the run for a reader of the file (the legends themselves are
# written in figures/*.gp, which know what each curve is); it is not used here.
# "options" are shockgas-sim's long options, passed through unchanged, so the
# parameter file is the complete record of every run. "parts" > 1 splits the
# realizations into separately stored parts (shockgas-sim --first-realization)
# merged by shockgas-merge: an interrupted build keeps the finished parts and
# continues where it stopped. Every run also checkpoints (shockgas-sim's
# default, every 300 s) and is started with --resume, so a killed build loses
# at most one checkpoint interval of the run it was in; and with
# --set-aside-other-runs, so that a run whose parameters were edited after it was
# stopped starts anew (its old checkpoint moved aside) instead of failing the build.

# _shockgas_stamp_target(<target> <stamp file> <directories> <programs...>): a target that writes
# <stamp file>, the hash of <directories> ("|"-separated) and of how they are built
# (cmake/SourceStamp.cmake), once <programs> are built. Simulations depend on the stamp, not on
# the programs, which relink at every commit (they embed git describe).
function(_shockgas_stamp_target target stamp directories)
  add_custom_target(${target}
    COMMAND ${CMAKE_COMMAND}
            -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            "-DDIRECTORIES=${directories}"
            "-DCOMPILER_INFO=${SHOCKGAS_SIM_COMPILER_INFO}"
            -DSTAMP=${stamp}
            -P ${PROJECT_SOURCE_DIR}/cmake/SourceStamp.cmake
    BYPRODUCTS ${stamp} ${stamp}.files
    COMMENT "Hashing what decides ${ARGN}'s numbers (its simulations rerun only when it changes)"
    VERBATIM)
  add_dependencies(${target} ${ARGN})
endfunction()

if(SHOCKGAS_PIPELINE_FROM_INSTALL)
  # An installed copy (cmake/installed-pipeline): no sources to hash; the runs
  # depend on the installed programs themselves, so a new installation reruns them.
  set(SHOCKGAS_SIM_STAMP "$<TARGET_FILE:shockgas-sim>")
  set(SHOCKGAS_TAIL_STAMP "$<TARGET_FILE:shockgas-tail>")
  set(SHOCKGAS_SPHERES_STAMP "$<TARGET_FILE:shockgas-spheres>")
  add_custom_target(shockgas_sim_stamp)
  add_custom_target(shockgas_tail_stamp)
  add_custom_target(shockgas_spheres_stamp)
else()
  # The simulator's stamp: sim/model, sim/io, sim/engines and sim/run
  # (SHOCKGAS_SIM_DIRECTORIES), the same hash the programs record as simulator_sha256.
  set(SHOCKGAS_SIM_STAMP "${CMAKE_BINARY_DIR}/shockgas-sim.stamp")
  _shockgas_stamp_target(shockgas_sim_stamp "${SHOCKGAS_SIM_STAMP}" "${SHOCKGAS_SIM_DIRECTORIES}"
                         shockgas-sim shockgas-merge)
  # The far-tail sampler's: sim/tail with the model and I/O it uses (SHOCKGAS_TAIL_DIRECTORIES).
  set(SHOCKGAS_TAIL_STAMP "${CMAKE_BINARY_DIR}/shockgas-tail.stamp")
  _shockgas_stamp_target(shockgas_tail_stamp "${SHOCKGAS_TAIL_STAMP}" "${SHOCKGAS_TAIL_DIRECTORIES}" shockgas-tail)
  # The disk and sphere gas's: sim/spheres with what it uses (SHOCKGAS_SPHERES_DIRECTORIES), the hash
  # its outputs record as spheres_sha256.
  set(SHOCKGAS_SPHERES_STAMP "${CMAKE_BINARY_DIR}/shockgas-spheres.stamp")
  _shockgas_stamp_target(shockgas_spheres_stamp "${SHOCKGAS_SPHERES_STAMP}" "${SHOCKGAS_SPHERES_DIRECTORIES}"
                         shockgas-spheres)
endif()

include(${PROJECT_SOURCE_DIR}/cmake/ShortestNumber.cmake)  # _shockgas_shortest_number

# Where a run writes before its output is final: <dir>/<name>.running.h5 for
# <dir>/<name>.h5. An interrupted shockgas-sim (Ctrl-C, SIGTERM, a killed
# build) still writes its file, marked "interrupted", and exits 130; were that
# the rule's OUTPUT, make would take it as up to date and the next build would
# feed a partial run to the analysis (seen: a killed paper build, then
# "no /snapshots" from shockgas-analyze). So the run writes the staged name and
# the rule (cmake/RunSimulation.cmake) renames it only after shockgas-sim exits 0;
# the next build reruns it and --resume continues from the staged name's checkpoint.
# The rule also records what the run was made from (<name>.h5.made) and keeps a run
# whose record matches when only file times make it look stale.
function(_shockgas_run_to output result)
  string(REGEX REPLACE "\\.h5$" ".running.h5" staged "${output}")
  set(${result} "${staged}" PARENT_SCOPE)
endfunction()

# _shockgas_manifest_line(<output> <staged> <arguments>): appends to the caller's `manifest` the line
# "<output><TAB><command>" for shockgas_figure_runs' simulations.tsv. The command runs the caller's
# `program` (shockgas-sim or shockgas-spheres) with
# <arguments> in this directory (as the rule does) and renames <staged> to <output> once it succeeds;
# every word is single-quoted for the shell.
function(_shockgas_manifest_line output staged arguments)
  set(quoted)
  foreach(word IN ITEMS "${CMAKE_CURRENT_BINARY_DIR}" "$<TARGET_FILE:${program}>" ${arguments} "${staged}" "${output}")
    string(REPLACE "'" "'\\''" word "${word}")
    list(APPEND quoted "'${word}'")
  endforeach()
  list(POP_FRONT quoted directory)
  list(POP_BACK quoted quoted_output)
  list(POP_BACK quoted quoted_staged)
  list(JOIN quoted " " command)
  set(manifest "${manifest}${output}\tcd ${directory} && ${command} && mv -f ${quoted_staged} ${quoted_output}\n"
      PARENT_SCOPE)
endfunction()

# shockgas_figure_runs(<figure>): defines the simulations of <figure> at the
# configured fidelity. Sets in the caller's scope:
#   <figure>_RUNS            run names, in file order
#   <figure>_<name>_H5       the run's output file
#   <figure>_PARAMETER_FILE  the JSON file
function(shockgas_figure_runs figure)
  set(parameter_file "${CMAKE_CURRENT_SOURCE_DIR}/${figure}.${SHOCKGAS_FIDELITY}.json")
  if(NOT EXISTS "${parameter_file}")
    message(FATAL_ERROR "no parameter file ${parameter_file}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${parameter_file}")
  file(READ "${parameter_file}" json)
  # "program": the simulator the runs' options are for: shockgas-sim (the ring, the default) or
  # shockgas-spheres (disks and spheres; one part a run: it has no merge yet). Each has its stamp.
  string(JSON program ERROR_VARIABLE no_program GET "${json}" program)
  if(no_program)
    set(program shockgas-sim)
  endif()
  if(program STREQUAL "shockgas-sim")
    set(stamp ${SHOCKGAS_SIM_STAMP})
    set(run_flags --quiet --resume --set-aside-other-runs)
  elseif(program STREQUAL "shockgas-spheres")
    set(stamp ${SHOCKGAS_SPHERES_STAMP})
    set(run_flags --resume)
  else()
    message(FATAL_ERROR "${parameter_file}: program '${program}' is neither shockgas-sim nor shockgas-spheres")
  endif()
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/${SHOCKGAS_FIDELITY}/${figure}")
  file(MAKE_DIRECTORY "${out_dir}")
  set(manifest "")  # _shockgas_manifest_line appends to it
  string(JSON run_count LENGTH "${json}" runs)
  math(EXPR last_run "${run_count} - 1")
  set(names)
  foreach(i RANGE ${last_run})
    string(JSON name GET "${json}" runs ${i} name)
    string(JSON parts ERROR_VARIABLE no_parts GET "${json}" runs ${i} parts)
    if(no_parts)
      set(parts 1)
    endif()
    string(JSON options GET "${json}" runs ${i} options)
    string(JSON option_count LENGTH "${options}")
    math(EXPR last_option "${option_count} - 1")
    set(args)
    set(realizations 1)
    foreach(j RANGE ${last_option})
      string(JSON key MEMBER "${options}" ${j})
      string(JSON value GET "${options}" ${key})
      _shockgas_shortest_number("${value}" value)
      if(key STREQUAL "realizations")
        set(realizations ${value})
      else()
        list(APPEND args "--${key}" "${value}")
      endif()
    endforeach()
    # The run's own record: rewritten only when its parameters change, so
    # editing one run in the JSON reruns only that run.
    set(h5 "${out_dir}/${name}.h5")
    string(REPLACE ";" " " args_text "${args} --realizations ${realizations} parts=${parts}")
    file(CONFIGURE OUTPUT "${out_dir}/${name}.args" CONTENT "${args_text}\n")
    if(parts EQUAL 1)
      _shockgas_run_to("${h5}" staged)
      set(run_arguments ${args} --realizations ${realizations} ${run_flags} --output "${staged}")
      _shockgas_manifest_line("${h5}" "${staged}" "${run_arguments}")
      add_custom_command(
        OUTPUT "${h5}"
        COMMAND ${CMAKE_COMMAND} -DOUTPUT=${h5} -DSTAGED=${staged} "-DINPUTS=${out_dir}/${name}.args|${stamp}"
                -P ${PROJECT_SOURCE_DIR}/cmake/RunSimulation.cmake -- $<TARGET_FILE:${program}> ${run_arguments}
        DEPENDS "${out_dir}/${name}.args" ${stamp}
        COMMENT "[${figure}/${SHOCKGAS_FIDELITY}] simulating ${name}: ${args_text}"
        VERBATIM)
    else()
      if(NOT program STREQUAL "shockgas-sim")
        message(FATAL_ERROR "${parameter_file}: run ${name} has parts, which only shockgas-sim's runs can have")
      endif()
      math(EXPR per_part "(${realizations} + ${parts} - 1) / ${parts}")
      set(part_files)
      set(first 0)
      while(first LESS realizations)
        math(EXPR count "${realizations} - ${first}")
        if(count GREATER per_part)
          set(count ${per_part})
        endif()
        set(part "${out_dir}/${name}.part${first}.h5")
        _shockgas_run_to("${part}" staged)
        set(run_arguments ${args} --realizations ${count} --first-realization ${first} --quiet --resume
                          --set-aside-other-runs --output "${staged}")
        _shockgas_manifest_line("${part}" "${staged}" "${run_arguments}")
        add_custom_command(
          OUTPUT "${part}"
          COMMAND ${CMAKE_COMMAND} -DOUTPUT=${part} -DSTAGED=${staged}
                  "-DINPUTS=${out_dir}/${name}.args|${SHOCKGAS_SIM_STAMP}"
                  -P ${PROJECT_SOURCE_DIR}/cmake/RunSimulation.cmake -- $<TARGET_FILE:shockgas-sim> ${run_arguments}
          DEPENDS "${out_dir}/${name}.args" ${SHOCKGAS_SIM_STAMP}
          COMMENT "[${figure}/${SHOCKGAS_FIDELITY}] simulating ${name}, realizations ${first}..+${count}"
          VERBATIM)
        list(APPEND part_files "${part}")
        math(EXPR first "${first} + ${count}")
      endwhile()
      add_custom_command(
        OUTPUT "${h5}"
        COMMAND shockgas-merge --output "${h5}" ${part_files}
        DEPENDS ${part_files}
        COMMENT "[${figure}/${SHOCKGAS_FIDELITY}] merging ${name}"
        VERBATIM)
    endif()
    list(APPEND names "${name}")
    set(${figure}_${name}_H5 "${h5}" PARENT_SCOPE)
  endforeach()
  # The figure's simulations as shell commands, for running them outside the build (a cluster's job
  # array, tools/paper-tier commands): each line is the output file, a tab, and the command that makes
  # it, the very command of its rule above. Put in place, the outputs are newer than their .args files
  # and the simulator's stamp, so the build takes them as made and goes on with merging and analysis.
  file(GENERATE OUTPUT "${out_dir}/simulations.tsv" CONTENT "${manifest}")
  set(${figure}_RUNS "${names}" PARENT_SCOPE)
  set(${figure}_PARAMETER_FILE "${parameter_file}" PARENT_SCOPE)
  set(${figure}_DIR "${out_dir}" PARENT_SCOPE)
endfunction()

# shockgas_plot(<figure> SCRIPT <gp> DATA <files...>): gnuplot writes
# <figure>.png and <figure>.pdf into the build's figures/ directory; reruns
# when the script, the shared style or the data change, never a simulation.
# Each figure's title names the fidelity and the shockgas version that drew it
# (style.gp asks version_program, built before every plot, for its version).
function(shockgas_plot figure)
  cmake_parse_arguments(ARG "" "SCRIPT" "DATA" ${ARGN})
  set(figure_dir "${CMAKE_BINARY_DIR}/figures/${SHOCKGAS_FIDELITY}")
  file(MAKE_DIRECTORY "${figure_dir}")
  set(outputs "${figure_dir}/${figure}.png" "${figure_dir}/${figure}.pdf")
  set(variables "datadir='${CMAKE_CURRENT_BINARY_DIR}/${SHOCKGAS_FIDELITY}/${figure}'; outbase='${figure_dir}/${figure}'; styledir='${PROJECT_SOURCE_DIR}/figures'; theorydir='${SHOCKGAS_THEORY_DIR}'; fidelity='${SHOCKGAS_FIDELITY}'; version_program='$<TARGET_FILE:shockgas-dump>'")
  add_custom_command(
    OUTPUT ${outputs}
    COMMAND ${GNUPLOT_EXECUTABLE} -e "${variables}; format='png'" "${PROJECT_SOURCE_DIR}/figures/${ARG_SCRIPT}"
    COMMAND ${GNUPLOT_EXECUTABLE} -e "${variables}; format='pdf'" "${PROJECT_SOURCE_DIR}/figures/${ARG_SCRIPT}"
    DEPENDS "${PROJECT_SOURCE_DIR}/figures/${ARG_SCRIPT}" "${PROJECT_SOURCE_DIR}/figures/style.gp" ${ARG_DATA}
    COMMENT "[${figure}/${SHOCKGAS_FIDELITY}] plotting ${figure}.png and ${figure}.pdf"
    VERBATIM)
  add_custom_target(${figure} DEPENDS ${outputs})
  # The theory's rule (paper_targets/CMakeLists.txt) is attached to every figure whose steps read
  # its files; built first through its own target, it is up to date before any of them looks, so
  # two figures built in parallel never run it twice at once (CMake's advice for an output that
  # several targets depend on).
  add_dependencies(${figure} shockgas_sim_stamp shockgas_spheres_stamp shockgas-analyze shockgas-dump shockgas_theory)
  set_property(GLOBAL APPEND PROPERTY SHOCKGAS_FIGURES ${figure})
endfunction()

# shockgas_step(<add_custom_command arguments>): add_custom_command for one of a figure's own steps
# (the far-tail sampler, an analysis, a dump), rerun also when its command changes. Make reruns a
# rule when an input is newer than its outputs, not when its command line changes: an option edited
# in a <figure>.cmake file (fig_tail's sampler options, fig5's --coarse-grain) or a run taken out of
# an aggregate's input list (which makes no remaining input newer) would leave the outputs stale.
# The call's arguments are written at configure time to <first output>.command, which
# file(CONFIGURE) rewrites only when they change, and the step depends on that file, as each run
# depends on its .args file (above).
function(shockgas_step)
  cmake_parse_arguments(ARG "VERBATIM;APPEND;USES_TERMINAL;COMMAND_EXPAND_LISTS"
                        "WORKING_DIRECTORY;COMMENT;MAIN_DEPENDENCY;DEPFILE;JOB_POOL"
                        "OUTPUT;COMMAND;DEPENDS;BYPRODUCTS;IMPLICIT_DEPENDS" ${ARGN})
  list(GET ARG_OUTPUT 0 first_output)
  string(REPLACE ";" "\n" command_text "${ARGN}")
  file(CONFIGURE OUTPUT "${first_output}.command" CONTENT "${command_text}\n" @ONLY)
  add_custom_command(${ARGN} DEPENDS "${first_output}.command")
endfunction()

# shockgas_gnuplot_vars(<figure> <results.h5> <prefix> <output.gp>): every attribute of an analysis's
# results file, its groups' included, as gnuplot variables <prefix>_<group>_<name> (shockgas-dump
# gnuplot-vars --recursive), for a figure's script to load.
function(shockgas_gnuplot_vars figure results prefix output)
  get_filename_component(name "${results}" NAME)
  shockgas_step(
    OUTPUT "${output}"
    COMMAND shockgas-dump gnuplot-vars "${results}" / --recursive --prefix ${prefix} --output "${output}"
    DEPENDS "${results}" shockgas-dump
    COMMENT "[${figure}] the numbers of ${name} for gnuplot"
    VERBATIM)
endfunction()
