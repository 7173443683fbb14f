# Fuzzing for scripts/test and scripts/fuzz: builds every libFuzzer target with clang
# (AddressSanitizer + UBSan instrumented, like the code they call) and runs each for a fixed
# time on a copy of its seed corpus (test/fuzz/corpus/<name>). A crash, leak, sanitizer report
# (UBSan included: not recoverable), hang (-timeout) or memory blow-up (-rss_limit_mb) fails;
# the input that caused it is left in build-fuzz/crashes/<name>/.

amha_fuzz_build() {
  local dir="$AMHA_ROOT/build-fuzz"
  # Everything in this build (libraries too) is instrumented for ASan/UBSan and coverage.
  CC=clang CXX=clang++ cmake -S "$AMHA_ROOT" -B "$dir" -DAMHA_BUILD_ROS=OFF -DAMHA_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=all -fno-omit-frame-pointer" \
    >&2 || return 1
  cmake --build "$dir" -j "$(nproc)" --target amha_fuzzers >&2
}

# amha_fuzz_run <seconds per target> [target ...]   (default: every target)
amha_fuzz_run() {
  local seconds=$1 dir="$AMHA_ROOT/build-fuzz" ok=0 f name work count=0
  shift
  local targets=("$@")
  if [ ${#targets[@]} -eq 0 ]; then
    for f in "$dir"/fuzz/*_fuzzer; do [ -x "$f" ] && targets+=("$(basename "$f" _fuzzer)"); done
  fi
  for name in "${targets[@]}"; do
    f="$dir/fuzz/${name}_fuzzer"
    [ -x "$f" ] || { echo "no fuzz target $name"; ok=1; continue; }
    count=$((count + 1))
    work=$(mktemp -d)
    cp -r "$AMHA_ROOT/test/fuzz/corpus/$name/." "$work/" 2>/dev/null || true
    mkdir -p "$dir/crashes/$name"
    amha_log "fuzzing $name for ${seconds}s"
    if ! UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
         "$f" "$work" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
         -artifact_prefix="$dir/crashes/$name/" -print_final_stats=0 >"$dir/crashes/$name.log" 2>&1; then
      echo "fuzz target $name FAILED; log: $dir/crashes/$name.log"; tail -30 "$dir/crashes/$name.log"
      ok=1
    fi
    rm -rf "$work"
  done
  [ "$count" -gt 0 ] || { echo "no fuzz targets were built"; return 1; }
  amha_log "$count fuzz target(s) ran for ${seconds}s each"
  return $ok
}
