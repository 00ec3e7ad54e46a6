# SPDX-License-Identifier: GPL-3.0-or-later
# Python cross-checks, label python. Each test makes its own input through a
# FIXTURES_SETUP test (never the figure build) and exits 77 -> SKIPPED without numpy/scipy/h5py.
if(NOT SHOCKGAS_PYTHON)
  message(STATUS "no Python interpreter: python tests not registered")
  return()
endif()
set(_py_work "${CMAKE_CURRENT_BINARY_DIR}/work/python")
file(MAKE_DIRECTORY "${_py_work}")
# Every test below gets python/ on Python's path from ctest (SHOCKGAS_TEST_PYTHONPATH, at the end).
get_property(_tests_before_python DIRECTORY PROPERTY TESTS)

add_test(NAME python.exact_ballistic COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_exact_ballistic.py
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.exact_ballistic PROPERTIES LABELS python TIMEOUT 600 SKIP_RETURN_CODE 77)

# Small sticky-gas run (N = 10^4, r = 0, R = 8) with snapshots and a histogram, and its decay fit.
add_test(NAME python.setup.run
         COMMAND shockgas-sim --particles 10000 --restitution 0 --t-max 10000 --realizations 8 --seed 7
                 --snapshot-times 100 --histogram-times 100 --quiet --output "${_py_work}/small.h5"
         WORKING_DIRECTORY "${_py_work}")
add_test(NAME python.setup.decay COMMAND shockgas-analyze decay "${_py_work}/small.h5" -o "${_py_work}/decay.h5"
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.setup.run PROPERTIES FIXTURES_SETUP python_run LABELS python TIMEOUT 120)
set_tests_properties(python.setup.decay PROPERTIES FIXTURES_SETUP python_decay FIXTURES_REQUIRED python_run
                     LABELS python TIMEOUT 60)

add_test(NAME python.refit_check COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/python/refit_check.py
                 "${_py_work}/decay.h5" --tolerance 1e-6 WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.refit_check PROPERTIES FIXTURES_REQUIRED "python_run;python_decay" LABELS python
                     TIMEOUT 120 SKIP_RETURN_CODE 77)
add_test(NAME python.schema COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_schema.py
                 "${_py_work}/small.h5" --doc ${PROJECT_SOURCE_DIR}/docs/cli-and-output.md WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.schema PROPERTIES FIXTURES_REQUIRED python_run LABELS python TIMEOUT 60
                     SKIP_RETURN_CODE 77)

# Clusters of a disk gas (shockgas-analyze clusters) recounted with scipy.ndimage.label and periodic
# merging (python/clusters_check.py): 2D, N = 20000, r = 0.8, 3 realizations, 3 snapshots, threshold 1.5,
# where clusters cross the box's faces (~4 s). Its velocity histograms' tail exponents
# (shockgas-analyze late-decay) refitted with scipy (python/tails_check.py).
add_test(NAME python.setup.spheres_run
         COMMAND shockgas-spheres -D 2 -N 20000 --phi 0.1 -r 0.8 -d 1e-2 -t 300 --snapshot-times 30,100,300
                 --histogram-times 1,30,300 --field-cells 32 -R 3 -j 1 -o "${_py_work}/disks.h5"
         WORKING_DIRECTORY "${_py_work}")
add_test(NAME python.setup.clusters
         COMMAND shockgas-analyze clusters "${_py_work}/disks.h5" --threshold 1.5 -o "${_py_work}/clusters.h5"
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.setup.spheres_run PROPERTIES FIXTURES_SETUP python_spheres LABELS python TIMEOUT 120)
set_tests_properties(python.setup.clusters PROPERTIES FIXTURES_SETUP python_clusters FIXTURES_REQUIRED python_spheres
                     LABELS python TIMEOUT 60)
add_test(NAME python.setup.late_decay
         COMMAND shockgas-analyze late-decay "${_py_work}/disks.h5" -o "${_py_work}/late.h5"
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.setup.late_decay PROPERTIES FIXTURES_SETUP python_late_decay
                     FIXTURES_REQUIRED python_spheres LABELS python TIMEOUT 60)
add_test(NAME python.tails_check COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/python/tails_check.py
                 "${_py_work}/late.h5" WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.tails_check PROPERTIES FIXTURES_REQUIRED "python_spheres;python_late_decay"
                     LABELS python TIMEOUT 60 SKIP_RETURN_CODE 77)
add_test(NAME python.clusters_check COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/python/clusters_check.py
                 "${_py_work}/clusters.h5" WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.clusters_check PROPERTIES FIXTURES_REQUIRED "python_spheres;python_clusters"
                     LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# The same recount in 3D (clusters joined through the faces of a periodic cube): N = 8000 spheres, r = 0.6,
# 2 realizations, 12^3 field cells, 3 snapshots, threshold 1.5 (~3 s).
add_test(NAME python.setup.spheres_run_3d
         COMMAND shockgas-spheres -D 3 -N 8000 --phi 0.1 -r 0.6 -d 1e-2 -t 300 --snapshot-times 10,100,300
                 --field-cells 12 -R 2 -j 1 -o "${_py_work}/spheres.h5"
         WORKING_DIRECTORY "${_py_work}")
add_test(NAME python.setup.clusters_3d
         COMMAND shockgas-analyze clusters "${_py_work}/spheres.h5" --threshold 1.5 -o "${_py_work}/clusters_3d.h5"
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.setup.spheres_run_3d PROPERTIES FIXTURES_SETUP python_spheres_3d LABELS python TIMEOUT 120)
set_tests_properties(python.setup.clusters_3d PROPERTIES FIXTURES_SETUP python_clusters_3d
                     FIXTURES_REQUIRED python_spheres_3d LABELS python TIMEOUT 60)
add_test(NAME python.clusters_check_3d COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/python/clusters_check.py
                 "${_py_work}/clusters_3d.h5" WORKING_DIRECTORY "${_py_work}")
set_tests_properties(python.clusters_check_3d PROPERTIES FIXTURES_REQUIRED "python_spheres_3d;python_clusters_3d"
                     LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)

# shockgas-sim against an independent plain event-driven reference written from the physics
# (python/reference_gas.py): ~70 small starts across r, delta, both sub-threshold mechanisms, masses,
# the seam, simultaneous collisions and collapse, every engine, at every sample (docs/reference-check.md;
# ~10 s of CPU).
add_test(NAME python.reference
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_reference_gas.py
                 $<TARGET_FILE:shockgas-sim> "${_py_work}/reference")
set_tests_properties(python.reference PROPERTIES LABELS python TIMEOUT 300 SKIP_RETURN_CODE 77)

# Exact prefactor (label physics): the exact engine at N = 10^6, 20 realizations, to t = 10^4
# (~25 s wall on 2 cores), T t^(2/3) against kappa from python/exact_ballistic.py.
add_test(NAME physics.setup.exact_prefactor
         COMMAND shockgas-sim --particles 1000000 --restitution 0 --t-max 10000 --realizations 20 --seed 1
                 --engine exact --quiet --output "${_py_work}/exact_1e6.h5"
         WORKING_DIRECTORY "${_py_work}")
set_tests_properties(physics.setup.exact_prefactor PROPERTIES FIXTURES_SETUP exact_prefactor LABELS physics TIMEOUT 300)
add_test(NAME physics.exact_prefactor COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/check_exact_prefactor.py
                 "${_py_work}/exact_1e6.h5" WORKING_DIRECTORY "${_py_work}")
set_tests_properties(physics.exact_prefactor PROPERTIES FIXTURES_REQUIRED exact_prefactor LABELS physics TIMEOUT 60
                     SKIP_RETURN_CODE 77)

# The Python module shockgas (python/shockgas) on every kind of file the programs write: runs,
# merged runs, checkpoints, analysis results, drift records, far-tail estimates, initial conditions
# (~2 s of CPU).
if(SHOCKGAS_BUILD_BENCH)
  set(_drift_program $<TARGET_FILE:shockgas-drift>)
else()
  set(_drift_program none)
endif()
add_test(NAME python.module
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_shockgas_module.py
                 $<TARGET_FILE:shockgas-sim> $<TARGET_FILE:shockgas-merge> $<TARGET_FILE:shockgas-analyze>
                 ${_drift_program} $<TARGET_FILE:shockgas-tail> "${_py_work}/module")
set_tests_properties(python.module PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)

# The scripts as a user runs them: a user's mistake is one line "<script>: error: ..." and exit
# status 2, never a traceback; what a check cannot judge fails rather than passes. Each makes its
# own small inputs (tests/python/script_checks.py has the shared assertions).
# tools/compare_engine_ensembles.py: one realization, other parameters, time grids or histograms
# refused; a NaN statistic fails (~1 s).
add_test(NAME python.compare_engine_ensembles
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_compare_engine_ensembles_cli.py
                 $<TARGET_FILE:shockgas-sim> "${_py_work}/compare_engine_ensembles")
set_tests_properties(python.compare_engine_ensembles PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# tools/tail_against_exact.py: a far-tail estimate against the exact Phi, with the uniform start's EB13
# shift; refusals (~25 s of CPU: the exact Phi's quadrature, once per table).
add_test(NAME python.tail_against_exact
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_tail_against_exact_cli.py
                 $<TARGET_FILE:shockgas-tail> "${_py_work}/tail_against_exact")
set_tests_properties(python.tail_against_exact PROPERTIES LABELS python TIMEOUT 300 SKIP_RETURN_CODE 77)
# python/refit_check.py: the run beside the results, checked against the recorded provenance; one or two
# realizations (sigma n/a, the count in the note); bad inputs (~1 s).
add_test(NAME python.refit_check_inputs
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_refit_check_cli.py
                 $<TARGET_FILE:shockgas-sim> $<TARGET_FILE:shockgas-analyze> "${_py_work}/refit_check_inputs")
set_tests_properties(python.refit_check_inputs PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# tools/reproduce-check: unreadable archives and a --compare-with that is no directory are exit 2, one line,
# no temporary left; --compare-with takes the code version from the compared files, so a build compared
# with its own archive reproduces after its checkout moved on, and a file of another version of the same
# simulator (the same simulator_sha256) reproduces; simulator_sha256 is provenance, not data (~14 s: packs
# a miniature build).
add_test(NAME python.reproduce_check_unreadable
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_reproduce_check_cli.py
                 "${_py_work}/reproduce_check_unreadable")
set_tests_properties(python.reproduce_check_unreadable PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# tools/fidelity_report.py: a fidelity the build lacks, no results, --check-readme without a file (< 1 s).
add_test(NAME python.fidelity_report_inputs
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_fidelity_report_cli.py
                 $<TARGET_FILE:shockgas-sim> "${_py_work}/fidelity_report_inputs")
set_tests_properties(python.fidelity_report_inputs PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# python/sticky_pav.py: histograms at small t, --hist-dir's chi2 with two realizations (counting errors),
# fits of too few times or realizations or of a time without spread, --compare's jackknife sigma against the
# spread over 100 ensembles, outputs that cannot be written, --init files it does not read (HDF5, no
# particles) and positions off the ring [0, L) (~22 s).
add_test(NAME python.sticky_pav_inputs
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_sticky_pav_cli.py
                 "${_py_work}/sticky_pav_inputs")
set_tests_properties(python.sticky_pav_inputs PROPERTIES LABELS python TIMEOUT 300 SKIP_RETURN_CODE 77)
# python/reference_gas.py: --compare checks the run's init_file_sha256; bad option values (r, delta, t_max,
# --sample-times, --max-events, --digits, ...) and a start simulate() refuses, one line each before any row; a
# missing module in one line (~10 s, one interpreter per refusal).
add_test(NAME python.reference_gas_inputs
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_reference_gas_cli.py
                 $<TARGET_FILE:shockgas-sim> "${_py_work}/reference_gas_inputs")
set_tests_properties(python.reference_gas_inputs PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# Every Python command-line script (python/*.py, tools/*.py, tools/reproduce-check): an unknown option,
# a missing argument, a bad number or choice is one line "<script>: error: ...", exit 2, through
# shockgas.cli.ArgumentParser; exact_ballistic.py --D not finite and > 0; --help is argparse's (~8 s, imports only).
add_test(NAME python.script_refusals
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_script_refusals_cli.py
                 "${_py_work}/script_refusals")
set_tests_properties(python.script_refusals PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# What the machine gives a script: numpy, h5py or the shockgas module missing (a copy where an installation
# puts the script), an output path that cannot be written (exact_ballistic.py, reproduce-check), and
# shockgas.cli's checks of outputs: one line "<script>: error: ...", exit 2; refit_check.py's skip, 77 (~3 s).
add_test(NAME python.script_environment
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_script_environment_cli.py
                 "${_py_work}/script_environment")
set_tests_properties(python.script_environment PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)
# Every output a Python script writes is written whole or not at all (shockgas.cli.atomic_output, the
# rule of the C++ programs' TextFile): interrupted by a file-size limit or Ctrl-C, sticky_pav.py's
# --clusters-out, --json, --hist-dir and exact_ballistic.py's --out-dir leave the previous file whole and
# no temporary; symbolic links, /dev/stdout, permissions (~3 s).
add_test(NAME python.atomic_output
         COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_atomic_output.py "${_py_work}/atomic_output")
set_tests_properties(python.atomic_output PROPERTIES LABELS python TIMEOUT 120 SKIP_RETURN_CODE 77)

get_property(_python_tests DIRECTORY PROPERTY TESTS)
list(REMOVE_ITEM _python_tests ${_tests_before_python})
set_property(TEST ${_python_tests} APPEND PROPERTY ENVIRONMENT "${SHOCKGAS_TEST_PYTHONPATH}")
