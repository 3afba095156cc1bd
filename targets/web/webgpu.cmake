# webgpu.cmake (included by CMakeLists.txt here, after it found node): the WebGPU side of issue 31 in
# Debian's chromium (headless, WebGPU through SwiftShader; label "browser"). Each test exits 77
# (skipped) without chromium; chromium without a WebGPU adapter fails them unless the environment
# sets PENUMBRA_WEBGPU_OPTIONAL=1 (then they skip).
find_program(PENUMBRA_CHROMIUM chromium)
if(NOT PENUMBRA_CHROMIUM)
    set(PENUMBRA_CHROMIUM /usr/bin/chromium) # absent: the tests report the skip
endif()
# "wgsl_compile": the compile harness (wgsl_compile.mjs) on hand-written modules: the broken one's
# error at its line and column, the valid one clean (the harness exits 1, hence the expression).
add_test(NAME wgsl_compile
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/wgsl_compile.mjs --chromium ${PENUMBRA_CHROMIUM}
                 ${CMAKE_CURRENT_SOURCE_DIR}/wgsl_fixtures)
set_tests_properties(wgsl_compile PROPERTIES LABELS browser TIMEOUT 60 SKIP_REGULAR_EXPRESSION "^skip: "
    PASS_REGULAR_EXPRESSION "wgsl_fixtures/broken\\.wgsl:6:21: error: unresolved value 'y'\nFAIL: 2 WGSL modules compiled, 1 clean, 1 errors")
# "wgsl_matrix": penumbra-gen --target wgsl over the matrix of wgsl_matrix.mjs, every module compiled
# with zero errors, the configurations wgsl does not have yet refused with a message naming wgsl.
if(TARGET penumbra-gen)
    add_test(NAME wgsl_matrix
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/wgsl_matrix.mjs --gen $<TARGET_FILE:penumbra-gen>
                     --out ${CMAKE_CURRENT_BINARY_DIR}/wgsl-matrix --chromium ${PENUMBRA_CHROMIUM})
    set_tests_properties(wgsl_matrix PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()
