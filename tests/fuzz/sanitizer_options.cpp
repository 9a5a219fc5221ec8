// fuzz: sanitizer defaults linked into every fuzz_* program (tests/fuzz/CMakeLists.txt), so a
// saved input reproduces the same way when the program is run by hand. ASAN_OPTIONS and
// UBSAN_OPTIONS in the environment still override each flag.

// Every allocation up to 1 MiB is filled with 0xbe (AddressSanitizer fills only the first 4 KiB
// by default): a reader that uses memory it never wrote then fails on every run, not only when
// the heap happens to hold the right leftovers.
extern "C" const char* __asan_default_options() {
    return "malloc_fill_byte=190:max_malloc_fill_size=1048576:detect_leaks=1";
}

extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }
