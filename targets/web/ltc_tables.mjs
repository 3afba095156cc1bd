// ltc_tables.mjs — what the Babylon.js tests (bundle_test.mjs, babylon_package_test.mjs) give the
// page for a RectAreaLight.
import path from "node:path";
import {fileURLToPath} from "node:url";

const modules = path.join(path.dirname(fileURLToPath(import.meta.url)), "node_modules");

// Babylon's RectAreaLight fetches its LTC tables from Babylon's CDN (assets.babylonjs.com), which a
// test cannot reach: the page gets the same fit (Heitz et al.'s, 64² half floats) from three's
// RectAreaLightTexturesLib, in Babylon's file layout (per texel LTC1 rgba then LTC2 rgba).
export async function ltcTables() {
    const {RectAreaLightTexturesLib} = await import(path.join(modules, "three/examples/jsm/lights/RectAreaLightTexturesLib.js"));
    RectAreaLightTexturesLib.init();
    const one = RectAreaLightTexturesLib.LTC_HALF_1.image.data, two = RectAreaLightTexturesLib.LTC_HALF_2.image.data;
    const out = new Uint16Array(2 * one.length);
    for (let p = 0; p < one.length / 4; ++p)
        for (let c = 0; c < 4; ++c) {
            out[8 * p + c] = one[4 * p + c];
            out[8 * p + 4 + c] = two[4 * p + c];
        }
    return Buffer.from(out.buffer);
}

export async function serveLtc(page, body) {
    await page.setRequestInterception(true);
    page.on("request", (request) => {
        if (/areaLightsLTC\.bin/.test(request.url()))
            request.respond({status: 200, contentType: "application/octet-stream", headers: {"Access-Control-Allow-Origin": "*"}, body});
        else request.continue();
    });
}
