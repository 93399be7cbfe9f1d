# The map loader's libFuzzer target and its seed writer. Included only by the workspace that
# `make fuzz` configures with clang and -DMRS_VPR_FUZZ=ON (.ws-fuzz, see the Makefile).

# Coverage feedback from the store's own code (SQLite is Debian's, not instrumented).
target_compile_options(${PROJECT_NAME}_store PRIVATE -fsanitize=fuzzer-no-link)

add_executable(map_database_fuzz_test EXCLUDE_FROM_ALL test/fuzz/map_database_fuzz_test.cpp)
target_link_libraries(map_database_fuzz_test ${PROJECT_NAME}_store -fsanitize=fuzzer)
target_compile_options(map_database_fuzz_test PRIVATE -fsanitize=fuzzer -Wall -Wextra)

add_executable(map_database_fuzz_test_seeds EXCLUDE_FROM_ALL test/fuzz/map_database_fuzz_test_seeds.cpp)
target_link_libraries(map_database_fuzz_test_seeds ${PROJECT_NAME}_store ${PROJECT_NAME}_core ${OpenCV_LIBS})
target_compile_options(map_database_fuzz_test_seeds PRIVATE -Wall -Wextra)
