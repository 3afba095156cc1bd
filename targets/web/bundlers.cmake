# bundlers.cmake (included by CMakeLists.txt here): the add-ons as a new user's project bundles
# them. "pack-web-packages" packs web/three and web/babylon (with the WebAssembly emitter they ship) into
# bundle-packs/; then one test per bundler, "bundler-vite", "bundler-esbuild", "bundler-webpack",
# "bundler-rollup" (bundle_test.mjs): a fresh project installs the tarballs offline, the bundler
# builds a page per package with no configuration beyond its documentation's for assets, and in
# chromium the page's shadow is checked ((lit with) / (lit without) = the add-on's visibility,
# the box's shadow there, update() after dispose() an error; on Babylon two lights on one material,
# StandardMaterial and PBRMaterial; with Vite also the React Three Fiber component of web/three/r3f/).
# The bundlers come from targets/web/node_modules (scripts/setup.sh).
get_property(bundlers_wasm GLOBAL PROPERTY PENUMBRA_EMITTER_WASM)
if(NOT bundlers_wasm)
    message(STATUS "penumbra: no WebAssembly emitter, so no bundler tests (the packages ship the emitter)")
    return()
endif()
set(bundle_packs ${CMAKE_CURRENT_BINARY_DIR}/bundle-packs)
add_test(NAME pack-web-packages
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/pack_packages.mjs --out ${bundle_packs} --wasm ${bundlers_wasm}
                 ${PROJECT_SOURCE_DIR}/web/three ${PROJECT_SOURCE_DIR}/web/babylon)
set_tests_properties(pack-web-packages PROPERTIES FIXTURES_SETUP penumbra_web_packs LABELS "browser;web" TIMEOUT 60)
# (timeouts: over twice each test's time in a cold run at -j2 on a loaded machine; Vite's build of
# the Babylon page, about a thousand modules of @babylonjs/core, is the longest part)
foreach(case IN ITEMS vite|480 esbuild|120 webpack|240 rollup|240)
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 bundler)
    list(GET parts 1 timeout)
    set(r3f "")
    if(bundler STREQUAL "vite") # and the React Three Fiber example's component (web/three/r3f/), in a Vite project
        set(r3f --tarball r3f=${bundle_packs}/penumbra-three.tgz)
    endif()
    add_test(NAME bundler-${bundler}
             COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/bundle_test.mjs --bundler ${bundler}
                     --work ${CMAKE_CURRENT_BINARY_DIR}/bundler-${bundler} --chromium ${PENUMBRA_CHROMIUM}
                     --tarball three=${bundle_packs}/penumbra-three.tgz --tarball babylon=${bundle_packs}/penumbra-babylon.tgz ${r3f})
    set_tests_properties(bundler-${bundler} PROPERTIES LABELS "browser;web" SKIP_RETURN_CODE 77 TIMEOUT ${timeout}
                         FIXTURES_REQUIRED penumbra_web_packs)
endforeach()
# "babylon-package" (babylon_package_test.mjs): penumbra-babylon's declarations checked with tsc
# against @babylonjs/core's, from the tarball in a fresh project; the example (web/babylon/example/,
# with web/babylon's npm ci) in chromium on both engines (Engine and WebGPUEngine): its light switch
# keeps its shadows; screenshots into babylon-package/images; and the Babylon bundle page unbundled
# on WebGPUEngine (two lights on a StandardMaterial and a PBRMaterial, as bundler-* check on WebGL2).
# (timeout: about 70 s warm alone; the WebGPU half renders through SwiftShader)
add_test(NAME babylon-package
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/babylon_package_test.mjs --tarball ${bundle_packs}/penumbra-babylon.tgz
                 --work ${CMAKE_CURRENT_BINARY_DIR}/babylon-package --web ${PROJECT_SOURCE_DIR}/web --chromium ${PENUMBRA_CHROMIUM}
                 --images ${CMAKE_CURRENT_BINARY_DIR}/babylon-package/images)
set_tests_properties(babylon-package PROPERTIES LABELS "browser;web" SKIP_RETURN_CODE 77 TIMEOUT 300
                     FIXTURES_REQUIRED penumbra_web_packs)
