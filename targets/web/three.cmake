# three.cmake (included by CMakeLists.txt here, after it found node and the essl300 bundles):
# the three.js add-on's tests.
find_program(PENUMBRA_CHROMIUM chromium)
if(NOT PENUMBRA_CHROMIUM)
    set(PENUMBRA_CHROMIUM /usr/bin/chromium) # absent: the tests report the skip
endif()
get_property(three_emitter_wasm GLOBAL PROPERTY PENUMBRA_EMITTER_WASM)
set(three_wasm "")
if(three_emitter_wasm)
    set(three_wasm --wasm ${three_emitter_wasm})
endif()
# The three.js add-on (web/three/, three from npm: scripts/setup.sh runs `npm ci` in web/three):
# "three" rebuilds each essl300 bundle's scene in three.js and checks the add-on against the
# desktop runtime (and, with the WebAssembly emitter built, the same configuration emitted in the
# page); "three-peers" measures three's PCF/VSM shadow maps and the add-on against the Embree
# truth of a small bundle (--quick: two settings of each); "three-emissions" checks that the
# emissions in web/three/emissions (written by the build, penumbra-web-emissions; not tracked) are
# what today's penumbra-gen writes.
# Beside the boxes bundles of ../gles, a room (issue 61): the built-in `room` scene, a closed room whose
# ceiling panel lies inside the scene's bounds (the ceiling behind the light's plane, the walls beside
# it outside the slicing pyramid: docs/model.md §1.2b), the camera inside; "babylon" runs it too.
set(three_room_bundle ${PROJECT_BINARY_DIR}/target_bundles/essl300-room)
add_test(NAME penumbra-bundle-essl300-room
         COMMAND $<TARGET_FILE:penumbra-export-bundle> --scene room --target essl300 --resolution 128 --size 64x64
                 --out ${three_room_bundle})
set_tests_properties(penumbra-bundle-essl300-room PROPERTIES FIXTURES_SETUP penumbra_room_bundle LABELS browser TIMEOUT 120)
add_test(NAME three
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/three_test.mjs --web ${PROJECT_SOURCE_DIR}/web
                 ${three_wasm} --chromium ${PENUMBRA_CHROMIUM} ${bundles} ${three_room_bundle})
set_tests_properties(three PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 180
                     FIXTURES_REQUIRED "penumbra_essl300_bundles;penumbra_room_bundle")
if(TARGET penumbra-export-bundle)
    set(peers_bundle ${PROJECT_BINARY_DIR}/target_bundles/three-peers-boxes)
    add_test(NAME penumbra-bundle-three-peers
             COMMAND $<TARGET_FILE:penumbra-export-bundle> --scene boxes --target essl300 --resolution 256
                     --size 96x96 --reference 8 --out ${peers_bundle})
    set_tests_properties(penumbra-bundle-three-peers PROPERTIES FIXTURES_SETUP penumbra_three_peers_bundle
                         LABELS browser TIMEOUT 120)
    add_test(NAME three-peers
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/three_peers.mjs --quick --web ${PROJECT_SOURCE_DIR}/web
                     --chromium ${PENUMBRA_CHROMIUM} ${peers_bundle})
    set_tests_properties(three-peers PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 180
                         FIXTURES_REQUIRED penumbra_three_peers_bundle)
endif()
if(TARGET penumbra-gen)
    add_test(NAME three-emissions
             COMMAND sh -c "rm -rf \"$1\" && \"$2\" --check \"$1\" \"$3\" && diff -r \"$1\" \"$4\" --exclude=regenerate.sh"
                     three-emissions ${CMAKE_CURRENT_BINARY_DIR}/three-emissions
                     ${PROJECT_SOURCE_DIR}/web/three/emissions/regenerate.sh $<TARGET_FILE:penumbra-gen>
                     ${PROJECT_SOURCE_DIR}/web/three/emissions)
    set_tests_properties(three-emissions PROPERTIES LABELS browser TIMEOUT 60)
endif()
# "three-package": the add-on as a user installs it (three_package_test.mjs): `npm pack` of web/three
# with the WebAssembly emitter it ships, installed offline into a fresh project beside vite,
# typescript, @types/three and three r180/r187 from targets/web/node_modules (scripts/setup.sh),
# tsc against @types/three r180 and r187, a Vite build with each three, and in chromium two
# shadowed lights on one material (two RectAreaLights; a RectAreaLight and a sun) and the example's
# light switch. The images of the two lights go to three-package/images.
if(three_emitter_wasm)
    add_test(NAME three-package
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/three_package_test.mjs --three ${PROJECT_SOURCE_DIR}/web/three
                     --work ${CMAKE_CURRENT_BINARY_DIR}/three-package --wasm ${three_emitter_wasm} --chromium ${PENUMBRA_CHROMIUM}
                     --images ${CMAKE_CURRENT_BINARY_DIR}/three-package/images)
    set_tests_properties(three-package PROPERTIES LABELS "browser;web" SKIP_RETURN_CODE 77 TIMEOUT 300)
else()
    message(STATUS "penumbra: no WebAssembly emitter, so no test of the npm package penumbra-three (it ships the emitter)")
endif()
# "three-webgpu": the add-on on three's WebGPURenderer (three_webgpu_test.mjs, WebGPU through
# SwiftShader as webgpu.cmake's tests; exits 77 without chromium, and without a WebGPU adapter only
# with PENUMBRA_WEBGPU_OPTIONAL=1) over wgsl bundles of boxes (rect, N-buffer; sun, Gaussian levels,
# with a MeshPhysicalNodeMaterial; rect, mipmap)
# and the tree (rect), and the corpus's teapot where scripts/get_corpus.sh fetched it (the corpus
# is not in the repository): the visibility against the desktop run within the oracle's bound, the
# node materials' light term, instanced/skinned/morphed casters, updates and dispose; and two add-ons
# (a RectAreaLight and a sun) on one node material, each scaling its own light's term only; the
# first bundle also on three r180. The room (issue 61) with the same checks but its visibility
# against the add-on's own WebGL2 visibility of the room (--against-webgl2, below).
if(TARGET penumbra-export-bundle)
    set(three_webgpu_cases "boxes-rect|--scene boxes --light rect --filter nbuffer|"
        "boxes-sun|--scene boxes --light sun --filter gaussian --light-size 20|:physical-node"
        "tree-rect|--scene tree --light rect --filter nbuffer|"
        # the mip chain (a pass a level on WebGPU): one sampled texture for all levels
        "boxes-mipmap|--scene boxes --light rect --filter mipmap|"
        # The room (issue 61; fourth field: its essl300 bundle): SwiftShader's 4 sub-pixel bits (llvmpipe's 8)
        # move a slice texel on the bookshelf's edge and the receivers by 1-2 mm, which in the self-shadow fade
        # puts 14 of 3047 interior pixels (up to 0.55) beyond 2·bound + q of the desktop's on WebGL2 and WebGPU
        # alike. So `three` (its 1%) holds the desktop comparison, and here the WebGPU visibility must equal
        # the add-on's WebGL2 visibility of that bundle in the same chromium within 2q at every pixel.
        "room-rect|--scene room --light rect --filter nbuffer||${three_room_bundle}")
    if(DEFINED ENV{XDG_CACHE_HOME})
        set(three_webgpu_teapot $ENV{XDG_CACHE_HOME}/penumbra/corpus/meshes/teapot.obj)
    else()
        set(three_webgpu_teapot $ENV{HOME}/.cache/penumbra/corpus/meshes/teapot.obj)
    endif()
    if(EXISTS ${three_webgpu_teapot})
        list(APPEND three_webgpu_cases "teapot-rect|--scene ${three_webgpu_teapot} --light rect --filter nbuffer|")
    else()
        message(STATUS "penumbra: no corpus (scripts/get_corpus.sh), so three-webgpu runs without the teapot")
    endif()
    set(three_webgpu_bundles "")
    set(three_webgpu_against "")
    foreach(case IN LISTS three_webgpu_cases)
        string(REPLACE "|" ";" parts "${case}")
        list(GET parts 0 name)
        list(GET parts 1 flags)
        list(GET parts 2 material)
        list(LENGTH parts fields)
        set(webgl2 "")
        if(fields GREATER 3)
            list(GET parts 3 webgl2)
        endif()
        separate_arguments(flags UNIX_COMMAND "${flags}")
        set(dir ${PROJECT_BINARY_DIR}/target_bundles/three-webgpu-${name})
        add_test(NAME penumbra-bundle-three-webgpu-${name}
                 COMMAND $<TARGET_FILE:penumbra-export-bundle> ${flags} --target wgsl --slices 16 --resolution 128
                         --size 64x64 --out ${dir})
        set_tests_properties(penumbra-bundle-three-webgpu-${name} PROPERTIES FIXTURES_SETUP penumbra_three_webgpu_bundles
                             LABELS browser TIMEOUT 120)
        if(webgl2)
            list(APPEND three_webgpu_against --against-webgl2 ${dir}${material} ${webgl2})
        else()
            list(APPEND three_webgpu_bundles ${dir}${material})
        endif()
    endforeach()
    # two add-ons on one node material (a RectAreaLight and a sun): emissions at 32² (six textures
    # each), so that both fit WebGPU's 16 sampled textures a stage beside three's own
    set(three_webgpu_two "")
    if(TARGET penumbra-gen)
        foreach(light IN ITEMS rect sun)
            set(dir ${CMAKE_CURRENT_BINARY_DIR}/three-webgpu/two-lights-${light})
            add_test(NAME penumbra-three-webgpu-two-lights-${light}
                     COMMAND $<TARGET_FILE:penumbra-gen> --target wgsl --light ${light} --filter nbuffer --slices 8 --resolution 32 --out ${dir})
            set_tests_properties(penumbra-three-webgpu-two-lights-${light} PROPERTIES FIXTURES_SETUP penumbra_three_webgpu_bundles
                                 LABELS browser TIMEOUT 60)
            list(APPEND three_webgpu_two ${dir})
        endforeach()
        list(PREPEND three_webgpu_two --two-lights)
    endif()
    # the first bundle again on three r180 (the other end of the peer range; npm ci here installs it)
    set(three_webgpu_r180 "")
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/node_modules/three-r180/build/three.webgpu.js)
        set(three_webgpu_r180 --three ${CMAKE_CURRENT_SOURCE_DIR}/node_modules/three-r180)
    endif()
    add_test(NAME three-webgpu
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/three_webgpu_test.mjs --web ${PROJECT_SOURCE_DIR}/web
                     --chromium ${PENUMBRA_CHROMIUM} --images ${CMAKE_CURRENT_BINARY_DIR}/three-webgpu/images ${three_webgpu_two}
                     ${three_webgpu_r180} ${three_webgpu_bundles} ${three_webgpu_against})
    set_tests_properties(three-webgpu PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 120
                         FIXTURES_REQUIRED "penumbra_three_webgpu_bundles;penumbra_room_bundle")
endif()
# "three-gltf": penumbra-three's GLTFLoader plugin for EXT_lights_area (web/three/gltf_lights_area.js;
# three_gltf_test.mjs, in node, well under a second): web/three/test/lights_area.gltf through three's
# GLTFLoader with r187 and r180, each rect light a RectAreaLight at its node's world position, facing
# its world -Z, of the extension's width and height; the disk light skipped with one warning.
set(three_gltf_r180 "")
if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/node_modules/three-r180/examples/jsm/loaders/GLTFLoader.js)
    set(three_gltf_r180 --three-r180 ${CMAKE_CURRENT_SOURCE_DIR}/node_modules/three-r180)
endif()
add_test(NAME three-gltf
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/three_gltf_test.mjs --three ${PROJECT_SOURCE_DIR}/web/three ${three_gltf_r180})
set_tests_properties(three-gltf PROPERTIES LABELS web TIMEOUT 60)
