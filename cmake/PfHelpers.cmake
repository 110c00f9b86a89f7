# pf_add_library / pf_add_executable / pf_add_test: every target gets the same warnings,
# include root and language level through the pf_warnings INTERFACE target.
add_library(pf_warnings INTERFACE)
target_compile_options(pf_warnings INTERFACE
    -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wno-missing-field-initializers)
target_include_directories(pf_warnings INTERFACE "${PROJECT_SOURCE_DIR}")
target_compile_features(pf_warnings INTERFACE cxx_std_20)

# pf_add_library(NAME SOURCES ... [DEPS ...])
function(pf_add_library name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_library(${name} STATIC ${ARG_SOURCES})
    target_link_libraries(${name} PUBLIC pf_warnings ${ARG_DEPS})
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# pf_add_executable(NAME SOURCES ... [DEPS ...])
function(pf_add_executable name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE pf_warnings ${ARG_DEPS})
endfunction()

# pf_add_test(NAME SOURCES ... [DEPS ...]): one GoogleTest binary, each case its own CTest test.
function(pf_add_test name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE pf_warnings ${ARG_DEPS} GTest::gtest GTest::gtest_main)
    target_compile_definitions(${name} PRIVATE
        PF_SOURCE_DIR="${PROJECT_SOURCE_DIR}" PF_BINARY_DIR="${PROJECT_BINARY_DIR}")
    gtest_discover_tests(${name} WORKING_DIRECTORY "${PROJECT_BINARY_DIR}"
        PROPERTIES ENVIRONMENT "PF_SOURCE_DIR=${PROJECT_SOURCE_DIR}" DISCOVERY_TIMEOUT 60)
endfunction()
