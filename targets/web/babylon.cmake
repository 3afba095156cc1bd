# babylon.cmake (included by CMakeLists.txt here, after three.cmake): the Babylon.js add-on's test
# over the essl300 bundles. "babylon" (babylon_test.mjs) rebuilds each bundle's scene in Babylon.js
# (web/babylon/test/, a right-handed scene with the bundle's triangles, light and camera) and checks
# the add-on's light frame and visibility against the desktop runtime, with three_test.mjs's
# functions and tolerances (2·bound + q on the interior pixels). Its packaging, materials and
# several lights: bundlers.cmake (bundler-*, babylon-package).
add_test(NAME babylon
         COMMAND ${PENUMBRA_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/babylon_test.mjs --web ${PROJECT_SOURCE_DIR}/web
                 --chromium ${PENUMBRA_CHROMIUM} ${bundles})
set_tests_properties(babylon PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 120
                     FIXTURES_REQUIRED penumbra_essl300_bundles)
