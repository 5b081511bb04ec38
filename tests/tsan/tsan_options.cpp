// Built-in TSan defaults of tsan_tests, so the binary fails on the first
// report however it is started (ctest sets the same through TSAN_OPTIONS,
// which overrides these). halt_on_error: a race fails the test instead of
// being printed and forgotten.
extern "C" const char* __tsan_default_options();
extern "C" const char* __tsan_default_options() { return "halt_on_error=1:second_deadlock_stack=1"; }
