# pf_add_library / pf_add_executable / pf_add_test: every target gets the same warnings,
# flags, include root and language level through the pf_warnings INTERFACE target.
add_library(pf_warnings INTERFACE)
target_compile_options(pf_warnings INTERFACE
    -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wno-missing-field-initializers)
target_include_directories(pf_warnings INTERFACE "${PROJECT_SOURCE_DIR}")
# Nothing reads errno after maths: without it sqrt compiles to one instruction, unguarded.
target_compile_options(pf_warnings INTERFACE -fno-math-errno)
target_compile_features(pf_warnings INTERFACE cxx_std_20)
# The version workers and the coordinator must agree on.
target_compile_definitions(pf_warnings INTERFACE PF_VERSION="${PROJECT_VERSION}")

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

# pf_add_test(NAME SOURCES ... [DEPS ...] [LABELS ...] [TIMEOUT SECONDS]): one GoogleTest
# binary, each case its own CTest test with the binary's labels (unit unless given) and a
# TIMEOUT per case (60 s unless given: the binary's slowest case on a loaded 2-core machine,
# with room). The TIMEOUT is also each case's COST: on a fresh clone (no CTestCostData.txt yet)
# `ctest -j` starts the binaries with long cases first, so the short ones fill the end of the run
# instead of one long case running alone there.
function(pf_add_test name)
    cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
    if(NOT ARG_TIMEOUT)
        set(ARG_TIMEOUT 60)
    endif()
    if(NOT ARG_LABELS)
        set(ARG_LABELS unit)
    endif()
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE pf_warnings ${ARG_DEPS} GTest::gtest GTest::gtest_main)
    target_compile_definitions(${name} PRIVATE
        PF_SOURCE_DIR="${PROJECT_SOURCE_DIR}" PF_BINARY_DIR="${PROJECT_BINARY_DIR}")
    # NO_PRETTY_VALUES: parameterised tests are named by their name generators alone, not by
    # gtest's printout of the parameter (bytes of pointers, for a struct of strings).
    gtest_discover_tests(${name} WORKING_DIRECTORY "${PROJECT_BINARY_DIR}" NO_PRETTY_VALUES
        PROPERTIES ENVIRONMENT "PF_SOURCE_DIR=${PROJECT_SOURCE_DIR}" TIMEOUT ${ARG_TIMEOUT}
                   COST ${ARG_TIMEOUT} LABELS "${ARG_LABELS}"
        DISCOVERY_TIMEOUT 60)
endfunction()

# pf_add_proto_library(NAME PROTO ...): runs protoc with the gRPC plugin on protos given
# relative to proto/ and builds the generated messages and service stubs into a library.
# Generated files live in the build tree only.
function(pf_add_proto_library name)
    set(sources)
    foreach(proto IN LISTS ARGN)
        string(REGEX REPLACE "\\.proto$" "" stem "${proto}")
        set(outputs
            "${CMAKE_CURRENT_BINARY_DIR}/${stem}.pb.cc" "${CMAKE_CURRENT_BINARY_DIR}/${stem}.pb.h"
            "${CMAKE_CURRENT_BINARY_DIR}/${stem}.grpc.pb.cc" "${CMAKE_CURRENT_BINARY_DIR}/${stem}.grpc.pb.h")
        add_custom_command(
            OUTPUT ${outputs}
            COMMAND protobuf::protoc --proto_path=${CMAKE_CURRENT_SOURCE_DIR}
                    --cpp_out=${CMAKE_CURRENT_BINARY_DIR} --grpc_out=${CMAKE_CURRENT_BINARY_DIR}
                    --plugin=protoc-gen-grpc=$<TARGET_FILE:gRPC::grpc_cpp_plugin>
                    ${CMAKE_CURRENT_SOURCE_DIR}/${proto}
            DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${proto}" protobuf::protoc gRPC::grpc_cpp_plugin
            COMMENT "protoc ${proto}")
        list(APPEND sources "${CMAKE_CURRENT_BINARY_DIR}/${stem}.pb.cc"
                            "${CMAKE_CURRENT_BINARY_DIR}/${stem}.grpc.pb.cc")
    endforeach()
    add_library(${name} STATIC ${sources})
    target_link_libraries(${name} PUBLIC protobuf::libprotobuf gRPC::grpc++)
    # Included as "photonfarm/v1/batch.pb.h".
    target_include_directories(${name} PUBLIC "${CMAKE_CURRENT_BINARY_DIR}")
    # protoc names each file's tables alike (schemas, file_default_instances): no unity build.
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON UNITY_BUILD OFF)
endfunction()

# pf_embed_text(TARGET FILE SYMBOL): the text of FILE (relative to the current source folder)
# compiled into TARGET as `pf::SYMBOL`, a std::string_view, from the header named after FILE
# with ".h" appended, included by its path from the source root ("client/x.gp.h").
function(pf_embed_text target file symbol)
    file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}/${file}")
    set(header "${PROJECT_BINARY_DIR}/embedded/${relative}.h")
    add_custom_command(
        OUTPUT "${header}"
        COMMAND ${CMAKE_COMMAND} -DINPUT=${CMAKE_CURRENT_SOURCE_DIR}/${file} -DOUTPUT=${header} -DSYMBOL=${symbol}
                -P "${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake"
        DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${file}" "${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake"
        COMMENT "embedding ${relative}")
    # A target of its own, as pf_add_shaders explains: attached to TARGET, the command and so
    # TARGET's compiles would wait for every library TARGET links.
    add_custom_target(${target}_${symbol} DEPENDS "${header}")
    add_dependencies(${target} ${target}_${symbol})
    target_include_directories(${target} PRIVATE "${PROJECT_BINARY_DIR}/embedded")
endfunction()

# pf_add_shaders(TARGET SHADER ...): compiles each GLSL compute shader (relative to the
# current source folder) to SPIR-V with glslc at build time, as a list of 32-bit words that
# TARGET's sources #include into an array by the shader's path from the source root with
# ".spv.inc" appended ("worker/backends/vulkan/shaders/x.comp.spv.inc"). Shaders include
# shared headers by their path from the source root; glslc's depfile tracks them.
# The commands belong to a target of their own, TARGET_shaders, which depends on nothing:
# attached to TARGET they would wait for TARGET's libraries to be linked, and glslc's
# optimiser (a minute for the largest shader) would then gate the end of a fresh build.
function(pf_add_shaders target)
    set(outputs)
    foreach(shader IN LISTS ARGN)
        file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}/${shader}")
        set(output "${PROJECT_BINARY_DIR}/embedded/${relative}.spv.inc")
        get_filename_component(output_dir "${output}" DIRECTORY)
        add_custom_command(
            OUTPUT "${output}"
            COMMAND ${CMAKE_COMMAND} -E make_directory "${output_dir}"
            COMMAND Vulkan::glslc --target-env=vulkan1.2 -O -Werror -mfmt=num -I "${PROJECT_SOURCE_DIR}"
                    -MD -MF "${output}.d" -o "${output}" "${CMAKE_CURRENT_SOURCE_DIR}/${shader}"
            DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${shader}"
            DEPFILE "${output}.d"
            COMMENT "glslc ${relative}")
        list(APPEND outputs "${output}")
    endforeach()
    add_custom_target(${target}_shaders DEPENDS ${outputs})
    add_dependencies(${target} ${target}_shaders)
    target_include_directories(${target} PRIVATE "${PROJECT_BINARY_DIR}/embedded")
endfunction()
