// The translation unit that builds the test executables' shared precompiled header
// (tests/CMakeLists.txt, fluidem_test_pch): GoogleTest, fmt and the standard headers the tests
// use, parsed once instead of in each of ~150 test files.
