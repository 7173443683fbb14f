# Sanitizer passes for scripts/test: the ROS-free unit tests built with AddressSanitizer +
# UndefinedBehaviorSanitizer, and the thread-sensitive ones (names containing Cancel,
# Concurrent or Thread) with ThreadSanitizer. Any report fails the pass.

# amha_sanitizer_pass <name> <-fsanitize flags> [gtest filter]
amha_sanitizer_pass() {
  local name=$1 flags=$2 filter=${3:-}
  local dir="$AMHA_ROOT/build-$name"
  cmake -S "$AMHA_ROOT" -B "$dir" -DAMHA_BUILD_ROS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="$flags -fno-omit-frame-pointer -fno-sanitize-recover=all" \
    -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" >&2 || return 1
  cmake --build "$dir" -j "$(nproc)" --target amha_unit_tests >&2 || return 1
  local ok=0 t start rc
  for t in "$dir"/tests/*; do
    [ -x "$t" ] || continue
    start=$(date +%s)
    if [ -n "$filter" ]; then
      # Skip binaries with no matching test (gtest would report 0 tests).
      "$t" --gtest_list_tests --gtest_filter="$filter" | grep -q '^  ' || continue
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
        UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 AMHA_SHARED_DATA="$AMHA_SHARED_DATA" \
        "$t" --gtest_filter="$filter" --gtest_brief=1
    else
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        AMHA_SHARED_DATA="$AMHA_SHARED_DATA" "$t" --gtest_brief=1
    fi
    rc=$?
    [ "$rc" -eq 0 ] || ok=1
    amha_log "$name: $(basename "$t") $([ "$rc" -eq 0 ] && echo passed || echo "FAILED (exit $rc)") in $(( $(date +%s) - start )) s"
  done
  return $ok
}
