# LIGHTHOUSE_FUZZ: every target of the build is compiled with AddressSanitizer,
# UndefinedBehaviorSanitizer (any report aborts) and libFuzzer's coverage instrumentation, so
# that the fuzz targets in this folder see, and are guided by, the libraries' code as well as
# their own. Included from the top-level CMakeLists.txt before any library is defined.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "LIGHTHOUSE_FUZZ needs clang, whose libFuzzer the fuzz targets link: "
                      "configure with -DCMAKE_CXX_COMPILER=clang++ (docs/reliability.md#fuzzing)")
endif()

# A target with the property LIGHTHOUSE_UNSANITIZED set is built without any of it (the .vdb
# probe, which caps its address space below what AddressSanitizer reserves at start-up).
# ubsan_ignorelist.txt: third-party headers whose deliberate UB would stop every run.
set(_lighthouse_sanitize -fsanitize=address,undefined -fno-sanitize-recover=undefined
    -fsanitize-ignorelist=${CMAKE_CURRENT_LIST_DIR}/ubsan_ignorelist.txt)
set(_lighthouse_sanitized "$<NOT:$<BOOL:$<TARGET_PROPERTY:LIGHTHOUSE_UNSANITIZED>>>")
add_compile_options(
  "$<${_lighthouse_sanitized}:${_lighthouse_sanitize};-fsanitize=fuzzer-no-link;-fno-omit-frame-pointer>")
add_link_options("$<${_lighthouse_sanitized}:${_lighthouse_sanitize}>")
