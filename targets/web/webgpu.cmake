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
# with zero errors, every configuration built by the WebGPU layout runner from its layout.json
# (pipelines, bind groups) and, with the WebAssembly emitter built, emitted by it byte for byte as
# penumbra-gen does; the configurations wgsl does not have yet refused with a message naming wgsl.
get_property(webgpu_emitter_wasm GLOBAL PROPERTY PENUMBRA_EMITTER_WASM)
set(webgpu_wasm "")
if(webgpu_emitter_wasm)
    set(webgpu_wasm --wasm ${webgpu_emitter_wasm})
endif()
if(TARGET penumbra-gen)
    add_test(NAME wgsl_matrix
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/wgsl_matrix.mjs --gen $<TARGET_FILE:penumbra-gen>
                     --out ${CMAKE_CURRENT_BINARY_DIR}/wgsl-matrix --web ${PROJECT_SOURCE_DIR}/web ${webgpu_wasm} --chromium ${PENUMBRA_CHROMIUM})
    set_tests_properties(wgsl_matrix PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()
# "webgpu_bundles": the WebGPU layout runner (web/three/penumbra_webgpu_runner.js) over bundles (boxes; tree and spider
# for occlusion textures) at 64x64
# exported with --target wgsl (the desktop GL run of glsl450, emission/ in WGSL) for every technique
# with WGSL (shadowmap, pcf, pcss, erosion, evsm, smrt, occlusion; rect and sun), each compared with the desktop run's
# image (webgpu_bundle_test.mjs); with the WebAssembly emitter, the playground's renderer switch on
# two of them (pcss rect, evsm sun) as well. Images of both runs and the playground's canvas go to
# webgpu-bundles/images.
if(TARGET penumbra-export-bundle)
    set(webgpu_cases
        "shadowmap-rect|--technique shadowmap --light rect" "shadowmap-sun|--technique shadowmap --light sun"
        "pcf-rect|--technique pcf --light rect --pcf-pattern grid --pcf-grid 3 --pcf-radius 0.15"
        "pcf-sun|--technique pcf --light sun --pcf-taps 16"
        "pcss-rect|--technique pcss --light rect --pcss-blockers 8 --pcss-filter 8"
        "pcss-sun|--technique pcss --light sun --pcss-blockers 8 --pcss-filter 8"
        "erosion-rect|--technique erosion --light rect" "erosion-sun|--technique erosion --light sun"
        # (a 256² shadow map: SwiftShader's 32-tap blur passes over 1024² take seconds)
        "evsm-rect|--technique evsm --light rect --shadow-resolution 256"
        "evsm-sun|--technique evsm --light sun --shadow-resolution 256"
        "smrt-rect|--technique smrt --light rect --shadow-resolution 256"
        "smrt-sun|--technique smrt --light sun --shadow-resolution 256"
        # occlusion textures: compared with the CPU oracle within its bound as well, with WebGPU's own
        # slices and with the desktop's; on the tree and a real mesh (Debian's assimp-testmodels) too
        "occlusion-rect|--slices 8 --resolution 128 --filter nbuffer --light rect"
        "occlusion-sun|--slices 8 --resolution 128 --filter gaussian --light sun --fusion correlated"
        "occlusion-mipmap|--slices 8 --resolution 128 --filter mipmap --light rect --fusion extent"
        "occlusion-array|--slices 8 --resolution 128 --packing array --filter mipmap --light rect"
        "occlusion-adaptive|--slices 8 --resolution 128 --slice-placement adaptive --light rect"
        # 64 slices: four slicing passes of four targets on WebGPU (the desktop writes bits, paper §3.7)
        "occlusion-64|--scene tree --slices 64 --resolution 128 --light rect"
        "occlusion-sat|--scene tree --slices 8 --resolution 128 --filter sat --packing array --light rect --fusion extent"
        "occlusion-volume|--scene tree --slices 8 --resolution 128 --packing volume --filter gaussian --light sun --fusion extent"
        "occlusion-tree|--scene tree --slices 8 --resolution 128 --filter nbuffer --light rect"
        "occlusion-spider|--scene /usr/share/assimp/models/OBJ/spider.obj --slices 16 --resolution 128 --filter nbuffer --light rect")
    set(webgpu_bundles "")
    foreach(case IN LISTS webgpu_cases)
        string(REPLACE "|" ";" parts "${case}")
        list(GET parts 0 name)
        list(GET parts 1 flags)
        separate_arguments(flags UNIX_COMMAND "${flags}")
        if(NOT flags MATCHES "--scene")
            list(PREPEND flags --scene boxes)
        endif()
        set(dir ${PROJECT_BINARY_DIR}/target_bundles/webgpu-${name})
        add_test(NAME penumbra-bundle-webgpu-${name}
                 COMMAND $<TARGET_FILE:penumbra-export-bundle> --target wgsl --size 64x64 ${flags} --out ${dir})
        set_tests_properties(penumbra-bundle-webgpu-${name} PROPERTIES FIXTURES_SETUP penumbra_webgpu_bundles LABELS browser TIMEOUT 120)
        # the playground's renderer switch on two of them (a page load and 512² frames each)
        if(name STREQUAL "pcss-rect" OR name STREQUAL "evsm-sun")
            list(APPEND webgpu_bundles --playground)
        endif()
        list(APPEND webgpu_bundles ${dir})
    endforeach()
    add_test(NAME webgpu_bundles
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/webgpu_bundle_test.mjs --web ${PROJECT_SOURCE_DIR}/web ${webgpu_wasm}
                     --chromium ${PENUMBRA_CHROMIUM} --images ${CMAKE_CURRENT_BINARY_DIR}/webgpu-bundles/images ${webgpu_bundles})
    set_tests_properties(webgpu_bundles PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 120
                         FIXTURES_REQUIRED penumbra_webgpu_bundles)
endif()
