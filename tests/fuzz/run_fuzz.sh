#!/usr/bin/env bash
# run_fuzz.sh build|run ...
#   build SOURCE_DIR BUILD_INFO_CPP OUT_DIR "HDF5_INCLUDE_DIRS" "HDF5_LIBRARIES"
#       compiles the libFuzzer harnesses with clang (-fsanitize=fuzzer,address,
#       undefined) from the library sources, separately from the main build,
#       whose compiler need not be clang. Exits 77 (ctest: skipped) with a
#       message when clang++ or its libFuzzer runtime is missing.
#   run OUT_DIR HARNESS CORPUS_DIR SECONDS
#       fuzzes for SECONDS starting from the corpus (not modified: new inputs
#       go to a scratch directory); a crash or sanitizer report fails.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
mode=$1
shift
if [ "$mode" = build ]; then
  source_dir=$1 build_info=$2 out_dir=$3 hdf5_includes=$4 hdf5_libraries=$5
  if ! command -v clang++ >/dev/null 2>&1; then
    echo "SKIPPED: clang++ not found; the fuzz harnesses need clang's libFuzzer (apt-get install clang)"
    exit 77
  fi
  mkdir -p "$out_dir"
  probe="$out_dir/probe.cpp"
  printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' > "$probe"
  if ! clang++ -fsanitize=fuzzer "$probe" -o "$out_dir/probe" >/dev/null 2>&1; then
    echo "SKIPPED: clang++ cannot link -fsanitize=fuzzer (libFuzzer runtime missing)"
    exit 77
  fi
  flags=(-std=c++20 -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
         -fno-sanitize-recover=undefined)
  # The rooms shockgas-sim is made of (sim/CMakeLists.txt), and the engines' private headers.
  rooms=(model io engines run cli)
  for room in "${rooms[@]}"; do flags+=(-I"$source_dir/sim/$room/include"); done
  flags+=(-I"$source_dir/sim/engines/src")
  # shockgas-sim's main also reads the validity map for its warning (analysis/src: two files that
  # need no GSL). The harness has no build tree, so no default map: empty names, none looked up.
  flags+=(-I"$source_dir/analysis/include" -DSHOCKGAS_PAPER_VALIDITY_MAP='""' -DSHOCKGAS_QUICK_VALIDITY_MAP='""')
  # CMake lists arrive ';'-separated.
  IFS=';' read -ra include_list <<< "$hdf5_includes"
  for dir in "${include_list[@]}"; do flags+=(-isystem "$dir"); done
  IFS=';' read -ra libraries <<< "$hdf5_libraries"
  objects=()
  # The rooms' sources (whatever their src/ folders hold) and the build's provenance file.
  # The fuzzers run one process: they take the one-rank stand-in of the
  # distributed layer, never its MPI version (which needs mpi.h and would
  # define the same symbols).
  sources=()
  for room in "${rooms[@]}"; do sources+=("$source_dir/sim/$room"/src/*.cpp); done
  sources+=("$source_dir/analysis/src/validity_map.cpp" "$source_dir/analysis/src/validity_warning.cpp")
  for src in "${sources[@]}" "$build_info"; do
    [ "$(basename "$src")" = distributed_mpi.cpp ] && continue
    obj="$out_dir/$(basename "${src%.cpp}").o"
    if [ ! -e "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find "$source_dir/sim" -name '*.hpp' -newer "$obj" -print -quit)" ] ||
       [ -n "$(find "$source_dir/analysis/include" -name '*.hpp' -newer "$obj" -print -quit)" ]; then
      clang++ "${flags[@]}" -c "$src" -o "$obj" &
    fi
    objects+=("$obj")
  done
  # shockgas-sim's main, renamed so the harness can call it.
  clang++ "${flags[@]}" -Dmain=shockgas_sim_main -c "$source_dir/sim/app/shockgas_sim.cpp" -o "$out_dir/shockgas_sim_app.o" &
  wait
  for harness in fuzz_init_file fuzz_config; do
    extra=()
    [ "$harness" = fuzz_config ] && extra=("$out_dir/shockgas_sim_app.o")
    clang++ "${flags[@]}" -fsanitize=fuzzer "$source_dir/tests/fuzz/$harness.cpp" "${extra[@]}" "${objects[@]}" \
      "${libraries[@]}" -lfmt -lcrypto -lpthread -o "$out_dir/$harness"
  done
  echo "built $out_dir/fuzz_init_file $out_dir/fuzz_config"
elif [ "$mode" = run ]; then
  out_dir=$1 harness=$2 corpus=$3 seconds=$4
  if [ ! -x "$out_dir/$harness" ]; then
    echo "SKIPPED: $out_dir/$harness was not built (no clang/libFuzzer)"
    exit 77
  fi
  scratch="$out_dir/corpus_$harness"
  mkdir -p "$scratch"
  # A fixed seed and a fixed number of runs make the ctest repeatable (the
  # same inputs on every machine); max_total_time only bounds a slow machine.
  # Leak detection off: HDF5 keeps global state on purpose. allocator_may_return_null:
  # on corrupt headers HDF5 itself asks malloc for absurd sizes (~2^44 bytes,
  # in H5C_protect); a plain malloc returns NULL there and HDF5 reports an error,
  # which is what happens outside the sanitizer, so let ASan do the same.
  # Structured inputs only in ctest: see fuzz_init_file.cpp on libhdf5's own
  # bugs with raw bytes.
  SHOCKGAS_FUZZ_STRUCTURED_ONLY=1 ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$out_dir/$harness" -seed=1 -runs=$((seconds * 300)) -max_total_time=$((seconds * 10)) -timeout=10 \
      -rss_limit_mb=2048 -max_len=4096 \
      -close_fd_mask=3 -artifact_prefix="$out_dir/crash_$harness-" "$scratch" "$corpus"
else
  echo "usage: run_fuzz.sh build|run ..." >&2
  exit 2
fi
