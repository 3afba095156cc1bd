// gltf_lights_area.d.ts — declarations of gltf_lights_area.js: a GLTFLoader plugin for EXT_lights_area.
import type {Object3D} from "three";
import type {GLTF, GLTFLoaderPlugin, GLTFParser} from "three/addons/loaders/GLTFLoader.js";

/** "EXT_lights_area", the extension's name (and the plugin's `name`). */
export const EXT_LIGHTS_AREA: "EXT_lights_area";

/**
 * A GLTFLoader plugin: a `RectAreaLight` for each node that references an `EXT_lights_area` light of
 * type `"rect"` (width `size·aspect`, height `size`, both times the node's largest absolute world
 * scale; colour and intensity as the extension says, defaults white and 1000 nits), placed by the
 * node's transform (both emit towards local −Z). `"disk"` lights are skipped with one `console.warn`.
 *
 * `new GLTFLoader().register((parser) => new GLTFLightsAreaExtension(parser))`
 */
export class GLTFLightsAreaExtension implements GLTFLoaderPlugin {
    constructor(parser: GLTFParser);
    readonly name: "EXT_lights_area";
    parser: GLTFParser;
    createNodeAttachment(nodeIndex: number): Promise<Object3D> | null;
    afterRoot(result: GLTF): Promise<void> | null;
}
