# babylon.cmake (included by CMakeLists.txt here, after three.cmake): the Babylon.js add-on's test
# over the essl300 bundles. "babylon" (babylon_test.mjs) rebuilds each bundle's scene in Babylon.js
# (web/babylon/test/, a right-handed scene with the bundle's triangles, light and camera) and checks
# the add-on's light frame and visibility against the desktop runtime, with three_test.mjs's
# functions and tolerances (2·bound + q on the interior pixels); and three.cmake's room bundle (a light
# inside a closed room, the camera inside). Its packaging, materials and
# several lights: bundlers.cmake (bundler-*, babylon-package). The material's light term and dispose(): here too.
# Both also run, once, the cut-out caster page (web/babylon/test/cutout.html, a few seconds), which
# reads the shipped emissions (web/three/emissions, written by the build: the "-cut" ones among them).
# TIMEOUT 180: the room bundle (issue 61) brought it to 65 s of the former 120 on a 2-core machine.
add_test(NAME babylon
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/babylon_test.mjs --web ${PROJECT_SOURCE_DIR}/web
                 --chromium ${PENUMBRA_CHROMIUM} ${bundles} ${three_room_bundle})
set_tests_properties(babylon PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 180
                     FIXTURES_REQUIRED "penumbra_essl300_bundles;penumbra_room_bundle")
# "babylon-webgpu": the same checks on Babylon's WebGPUEngine (--engine webgpu: WebGPU through
# SwiftShader as three-webgpu, the canvas rendered offscreen: offscreen_canvas.mjs) over
# three-webgpu's wgsl bundles of the same scenes (rect N-buffer, sun Gaussian, rect mipmap, the tree), and its
# room: that one's visibility checked against the add-on's own on Engine (WebGL2) with the essl300 room in the same
# chromium, every pixel within 2q, not against the desktop's (SwiftShader's 4 sub-pixel bits against llvmpipe's 8
# put 14 of its 3047 interior pixels beyond 2·bound + q on both engines: "babylon" holds that, with its 1%).
# TIMEOUT 180: the room brought it to 38–58 s on a 2-core machine (the upper end under load), near half of 120.
if(TARGET penumbra-export-bundle)
    set(babylon_webgpu_bundles "")
    foreach(name IN ITEMS boxes-rect boxes-sun boxes-mipmap tree-rect)
        list(APPEND babylon_webgpu_bundles ${PROJECT_BINARY_DIR}/target_bundles/three-webgpu-${name})
    endforeach()
    add_test(NAME babylon-webgpu
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/babylon_test.mjs --web ${PROJECT_SOURCE_DIR}/web --engine webgpu
                     --chromium ${PENUMBRA_CHROMIUM} ${babylon_webgpu_bundles}
                     --against-webgl2 ${PROJECT_BINARY_DIR}/target_bundles/three-webgpu-room-rect ${three_room_bundle})
    set_tests_properties(babylon-webgpu PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 180
                         FIXTURES_REQUIRED "penumbra_three_webgpu_bundles;penumbra_room_bundle")
endif()
