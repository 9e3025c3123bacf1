#!/usr/bin/env bash
# Robustness checks (docs/robustness.md says what each one proves).
#
#   bash scripts/robustness.sh ci          # what CI runs: tests + asan + valgrind + fuzz-ci
#   bash scripts/robustness.sh tests       # tests/hard_cases.rs, threads.rs, restart.rs, …;
#                                          # harness/tests/size_limits.rs, check_finds.rs
#   bash scripts/robustness.sh asan        # C/Fortran hosts + threaded C host, ASan+UBSan
#   bash scripts/robustness.sh valgrind    # memcheck of the threaded C host (the single-
#                                          # threaded hosts: cargo test --test hosts)
#   bash scripts/robustness.sh fuzz-ci [S] # every fuzz target S seconds (default 15)
#   bash scripts/robustness.sh fuzz-long [S]  # every target S seconds (default 240), then
#                                          # minimizes the corpus (cargo fuzz cmin); nightly
#   bash scripts/robustness.sh tsan        # the ThreadSanitizer attempts (see the doc)
#
# Fuzzing uses libFuzzer with ASan wherever a nightly toolchain exists: through
# `cargo +nightly fuzz` when cargo-fuzz is installed, else built here with the flags cargo
# fuzz passes (mode "nightly"). With stable only (the usual CI machine) the same targets
# are built as plain binaries (fuzz/Cargo.toml feature `replay`) that replay the committed
# corpus and then mutate it at random for the time budget: a random search, not
# coverage-guided fuzzing. The line "fuzz mode:" says which one ran; ROBUST_FUZZ=replay
# or ROBUST_FUZZ=nightly forces a mode.
#
# Build products go to $CARGO_TARGET_DIR (default target/) and $ROBUST_DIR (default
# $CARGO_TARGET_DIR/robustness). Needs gcc, gfortran, make; valgrind for `valgrind`.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
OUT=${ROBUST_DIR:-$TARGET/robustness}
mkdir -p "$OUT"
TARGETS=(jointlin_linearize jointlin_uinter jointlin_uexternaldb scene_check deck_check)

log() { printf '== %s\n' "$*"; }

lib() {
    CARGO_TARGET_DIR=$TARGET cargo build --release -q -p jointlin --lib
    LIBDIR=$TARGET/release
    test -f "$LIBDIR/libjointlin.so"
    soname_link "$LIBDIR"
}

# Programs load libjointlin.so by its SONAME (libjointlin.so.MAJOR, set by build.rs);
# cargo's output directory gets a link of that name.
soname_link() { # dir
    local so
    so=$(readelf -d "$1/libjointlin.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
    [ -z "$so" ] || [ -e "$1/$so" ] || ln -s libjointlin.so "$1/$so"
}

# Runs a host program in a fresh directory; fails on a nonzero exit or any sanitizer
# report on stderr.
run_host() { # name dir program [config]
    local name=$1 dir=$2 prog=$3 cfg=${4:-}
    rm -rf "$dir" && mkdir -p "$dir"
    local start=$SECONDS
    if ! (cd "$dir" && JOINTLIN_CONFIG=$cfg "$prog" >stdout.txt 2>stderr.txt); then
        cat "$dir/stderr.txt" >&2
        echo "FAIL: $name exited nonzero" >&2
        return 1
    fi
    if grep -qE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|WARNING: ThreadSanitizer' "$dir/stderr.txt"; then
        cat "$dir/stderr.txt" >&2
        echo "FAIL: $name: sanitizer report" >&2
        return 1
    fi
    echo "ok: $name ($(wc -l <"$dir/stdout.txt") records, $((SECONDS - start)) s)"
}

cmd_tests() {
    log "tests: hard_cases, whole_range, threads, restart, restart_files, store_scale (release)"
    CARGO_TARGET_DIR=$TARGET cargo test --release -p jointlin --test hard_cases \
        --test whole_range --test threads --test restart --test restart_files --test store_scale
    log "tests: scene size limits, check finds what run finds (release)"
    CARGO_TARGET_DIR=$TARGET cargo test --release -p jointlin-harness --test size_limits \
        --test check_finds
}

# The hosts built with gcc/gfortran -fsanitize=address,undefined against a
# libjointlin.so in $1 ("plain": the stable release build, where ASan sees the hosts'
# accesses and the library's malloc/free/memcpy; "instrumented": built by nightly rustc
# with -Zsanitizer=address, so the library's own loads and stores are checked too).
cmd_asan() {
    lib
    asan_hosts plain "$LIBDIR"
    if cargo +nightly --version >/dev/null 2>&1; then
        RUSTFLAGS="-Zsanitizer=address -Cunsafe-allow-abi-mismatch=sanitizer" \
            CARGO_TARGET_DIR=$TARGET/asan-lib cargo +nightly build --release -q -p jointlin --lib \
            --target x86_64-unknown-linux-gnu
        soname_link "$TARGET/asan-lib/x86_64-unknown-linux-gnu/release"
        asan_hosts instrumented "$TARGET/asan-lib/x86_64-unknown-linux-gnu/release"
    else
        no_nightly "libjointlin.so itself not ASan-instrumented (hosts are)"
    fi
}

# Without a nightly toolchain the weaker run is said; on CI (CI set, neither empty nor
# "false", as tests/tools/mod.rs reads it) it fails instead: scripts/test.sh installs
# nightly first.
no_nightly() {
    if [ -n "${CI:-}" ] && [ "${CI:-}" != false ]; then
        echo "no nightly Rust toolchain on CI: $1; run  rustup toolchain install nightly --profile minimal" >&2
        exit 1
    fi
    echo "no nightly toolchain: $1"
}

asan_hosts() {
    local kind=$1 LIBDIR=$2
    log "asan ($kind libjointlin.so): C and Fortran hosts and the threaded C host"
    local san="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
    local b=$OUT/asan-$kind
    make -s -f harness/c/Makefile BUILD="$b/c" JOINTLIN_LIBDIR="$LIBDIR" JOINTLIN_INCDIR="$ROOT/include" \
        CFLAGS="-O1 -g -std=c99 -Wall -Wextra -Werror -pedantic $san"
    make -s -f fortran-shim/Makefile BUILD="$b/shim" JOINTLIN_LIBDIR="$LIBDIR" \
        FFLAGS="-O1 -g -fPIC -Wall -Wno-unused-dummy-argument -Wno-unused-variable $san"
    make -s -f harness/fortran/Makefile BUILD="$b/fortran" SHIM="$b/shim" JOINTLIN_LIBDIR="$LIBDIR" \
        FFLAGS="-O1 -g -Wall -Wno-unused-dummy-argument $san"
    gcc -O1 -g -std=c11 -Wall -Wextra -Werror -pthread $san -I"$ROOT/include" \
        scripts/robustness/uinter_threads.c -o "$b/uinter_threads" \
        -L"$LIBDIR" -Wl,-rpath,"$LIBDIR" -l:libjointlin.so -lm
    export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    run_host "C block_stick" "$b/run/c-block_stick" "$b/c/block_stick"
    run_host "C sweep" "$b/run/c-sweep" "$b/c/sweep"
    run_host "Fortran block_stick" "$b/run/f-block_stick" "$b/fortran/block_stick" "$ROOT/harness/fortran/block_stick.cfg"
    run_host "Fortran sweep" "$b/run/f-sweep" "$b/fortran/sweep" "$ROOT/harness/fortran/sweep.cfg"
    run_host "C uinter_threads (8 pthreads)" "$b/run/uinter_threads" "$b/uinter_threads"
}

cmd_valgrind() {
    lib
    log "valgrind memcheck: threaded C host (single-threaded hosts: cargo test --test hosts)"
    local b=$OUT/valgrind
    mkdir -p "$b"
    gcc -O1 -g -std=c11 -Wall -Wextra -Werror -pthread -I"$ROOT/include" \
        scripts/robustness/uinter_threads.c -o "$b/uinter_threads" \
        -L"$LIBDIR" -Wl,-rpath,"$LIBDIR" -l:libjointlin.so -lm
    valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite --quiet \
        "$b/uinter_threads"
}

have_cargo_fuzz() {
    cargo +nightly --version >/dev/null 2>&1 && cargo +nightly fuzz --version >/dev/null 2>&1
}

# How the targets get libFuzzer: "cargo-fuzz" (nightly + cargo fuzz), "nightly" (nightly
# without cargo-fuzz: the same instrumented build, made here with the flags cargo fuzz
# passes), or "replay" (stable only). ROBUST_FUZZ=replay|nightly forces a mode.
fuzz_mode() {
    case "${ROBUST_FUZZ:-auto}" in
    replay | nightly) echo "$ROBUST_FUZZ" ;;
    *)
        if have_cargo_fuzz; then
            echo cargo-fuzz
        elif cargo +nightly --version >/dev/null 2>&1; then
            echo nightly
        else
            echo replay
        fi
        ;;
    esac
}

FUZZ_TRIPLE=$(rustc -vV | sed -n 's/^host: //p')
FUZZ_NIGHTLY_DIR=$TARGET/fuzz-nightly

# What `cargo fuzz build` does: sanitizer coverage for libFuzzer, --cfg fuzzing, ASan,
# debug assertions and overflow checks; libfuzzer-sys compiles libFuzzer (needs a C++
# compiler). Binaries in $FUZZ_NIGHTLY_DIR/$FUZZ_TRIPLE/release.
build_libfuzzer_nightly() {
    RUSTFLAGS="--cfg fuzzing -Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares -Cdebug-assertions -Coverflow-checks \
-Zsanitizer=address" \
        cargo +nightly build -q --release --manifest-path fuzz/Cargo.toml \
        --target "$FUZZ_TRIPLE" --target-dir "$FUZZ_NIGHTLY_DIR" --bins
}

# Runs libFuzzer target $1 on corpus directory $2 for $3 s (log in $OUT/fuzz-$1.log).
run_libfuzzer() { # target corpus secs
    local t=$1 c=$2 secs=$3 ok=0
    mkdir -p "fuzz/artifacts/$t"
    local opts=(-max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1)
    if [ "$MODE" = cargo-fuzz ]; then
        cargo +nightly fuzz run --target-dir "$TARGET/fuzz" "$t" "$c" -- "${opts[@]}" \
            >"$OUT/fuzz-$t.log" 2>&1 || ok=1
    else
        "$FUZZ_NIGHTLY_DIR/$FUZZ_TRIPLE/release/$t" "$c" "${opts[@]}" \
            -artifact_prefix="fuzz/artifacts/$t/" >"$OUT/fuzz-$t.log" 2>&1 || ok=1
    fi
    if [ $ok != 0 ]; then
        tail -40 "$OUT/fuzz-$t.log" >&2
        echo "FAIL: fuzz target $t (artifact in fuzz/artifacts/$t)" >&2
    fi
    return $ok
}

cmd_fuzz_ci() {
    local secs=${1:-15}
    MODE=$(fuzz_mode)
    if [ "$MODE" = replay ]; then
        [ "${ROBUST_FUZZ:-auto}" = replay ] || no_nightly "fuzzing replays the corpus with random mutation, not coverage-guided"
        log "fuzz mode: stable replay + random mutation (no nightly), $secs s per target"
        CARGO_TARGET_DIR=$TARGET/fuzz-replay cargo build --release -q \
            --manifest-path fuzz/Cargo.toml --no-default-features --features replay
        for t in "${TARGETS[@]}"; do
            "$TARGET/fuzz-replay/release/$t" "fuzz/corpus/$t" --seconds "$secs" --seed "$RANDOM"
        done
        return
    fi
    log "fuzz mode: $MODE (libFuzzer + ASan, nightly), $secs s per target"
    [ "$MODE" = cargo-fuzz ] || build_libfuzzer_nightly
    for t in "${TARGETS[@]}"; do
        # A scratch copy of the corpus: CI must not grow the committed one.
        local c=$OUT/fuzz-corpus/$t
        rm -rf "$c" && mkdir -p "$c" && cp fuzz/corpus/"$t"/* "$c"/
        run_libfuzzer "$t" "$c" "$secs" || return 1
        echo "ok: $t $(grep -E '^Done' "$OUT/fuzz-$t.log")"
    done
}

cmd_fuzz_long() {
    local secs=${1:-240}
    MODE=$(fuzz_mode)
    [ "$MODE" != replay ] || { echo "fuzz-long needs a nightly toolchain" >&2; exit 1; }
    [ "$MODE" = cargo-fuzz ] || build_libfuzzer_nightly
    for t in "${TARGETS[@]}"; do
        log "fuzz $t for $secs s ($MODE)"
        run_libfuzzer "$t" "fuzz/corpus/$t" "$secs" || exit 1
        grep -E '^(stat::number_of_executed_units|Done)' "$OUT/fuzz-$t.log"
        if [ "$MODE" = cargo-fuzz ]; then
            cargo +nightly fuzz cmin --target-dir "$TARGET/fuzz" "$t" "fuzz/corpus/$t" 2>&1 | tail -1
        else
            # cmin by hand: merge the corpus into an empty directory, keep the result.
            local m=$OUT/fuzz-min/$t
            rm -rf "$m" && mkdir -p "$m"
            "$FUZZ_NIGHTLY_DIR/$FUZZ_TRIPLE/release/$t" -merge=1 -set_cover_merge=1 "$m" \
                "fuzz/corpus/$t" >"$OUT/fuzz-min-$t.log" 2>&1
            rm -rf "fuzz/corpus/$t" && cp -r "$m" "fuzz/corpus/$t"
            echo "corpus $t: $(ls "fuzz/corpus/$t" | wc -l) files"
        fi
    done
}

cmd_tsan() {
    # Documented in docs/robustness.md: with no rust-src for -Zbuild-std, std's locks are
    # not instrumented and TSan reports false races inside std::sync-protected code.
    cargo +nightly --version >/dev/null 2>&1 || { echo "tsan needs a nightly toolchain" >&2; exit 1; }
    log "tsan: tests/threads.rs built with -Zsanitizer=thread (std uninstrumented)"
    RUSTFLAGS="-Zsanitizer=thread -Cunsafe-allow-abi-mismatch=sanitizer" \
        CARGO_TARGET_DIR=$TARGET/tsan cargo +nightly test --release -p jointlin --test threads \
        --target x86_64-unknown-linux-gnu -- --test-threads 1 2>&1 | tee "$OUT/tsan.txt" |
        grep -E '^test |test result' || true
    echo "TSan reports: $(grep -c '^WARNING: ThreadSanitizer' "$OUT/tsan.txt" || true) (see $OUT/tsan.txt)"
}

case ${1:-ci} in
ci)
    start=$SECONDS
    cmd_tests
    cmd_asan
    cmd_valgrind
    cmd_fuzz_ci 15
    log "robustness ci: all passed in $((SECONDS - start)) s"
    ;;
tests) cmd_tests ;;
asan) cmd_asan ;;
valgrind) cmd_valgrind ;;
fuzz-ci) cmd_fuzz_ci "${2:-15}" ;;
fuzz-long) cmd_fuzz_long "${2:-240}" ;;
tsan) cmd_tsan ;;
*)
    sed -n '2,20p' "$0"
    exit 2
    ;;
esac
