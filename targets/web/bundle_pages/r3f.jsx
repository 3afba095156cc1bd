// r3f.jsx — the React Three Fiber page of the bundler test (bundle_test.mjs, Vite only): the hook
// and component of web/three/r3f/usePenumbraShadows.js (copied into the project, as a user copies
// the example) in an R3F scene: a ground, a box casting, a RectAreaLight with <PenumbraShadows>.
// window.bundleCheck.run() returns the canvas with the component mounted and after it unmounted
// (the add-on disposed, the material's own shader back), and what the add-on counted.
import {useRef, useState} from "react";
import {createRoot} from "react-dom/client";
import {Canvas} from "@react-three/fiber";
import {RectAreaLightUniformsLib} from "three/addons/lights/RectAreaLightUniformsLib.js";
import {PenumbraShadows} from "./usePenumbraShadows.js";

RectAreaLightUniformsLib.init();
const SIZE = 96;
const loaded = [];
let setShadowsOn = null;

function Scene({shadowsOn}) {
    const light = useRef();
    return (
        <>
            <rectAreaLight ref={light} args={[0xffffff, 4, 1.2, 1.2]} position={[-1, 4, 0]} rotation={[-Math.PI / 2, 0, 0]} />
            <mesh rotation={[-Math.PI / 2, 0, 0]} receiveShadow>
                <planeGeometry args={[10, 10]} />
                <meshStandardMaterial roughness={1} metalness={0} />
            </mesh>
            <mesh position={[0, 1, 0]} castShadow>
                <boxGeometry args={[1.2, 2, 1.2]} />
                <meshStandardMaterial />
            </mesh>
            {shadowsOn && <PenumbraShadows light={light} onLoad={(s) => loaded.push(s)} />}
        </>
    );
}

function App() {
    const [shadowsOn, set] = useState(true);
    setShadowsOn = set;
    return (
        <Canvas dpr={1} gl={{antialias: false, preserveDrawingBuffer: true}} style={{width: `${SIZE}px`, height: `${SIZE}px`}}
                camera={{position: [0, 7, 5], fov: 50}} onCreated={({camera}) => camera.lookAt(0, 0, 0)}>
            <Scene shadowsOn={shadowsOn} />
        </Canvas>
    );
}

const frames = (n) => new Promise((resolve) => {
    const step = (k) => (k === 0 ? resolve() : requestAnimationFrame(() => step(k - 1)));
    step(n);
});

function pixels() {
    const canvas = document.querySelector("canvas");
    const c = document.createElement("canvas");
    c.width = canvas.width;
    c.height = canvas.height;
    const ctx = c.getContext("2d");
    ctx.drawImage(canvas, 0, 0);
    return {width: c.width, height: c.height, rgba: Array.from(ctx.getImageData(0, 0, c.width, c.height).data)};
}

async function run() {
    for (let i = 0; i < 600 && !(loaded.length && loaded[0].info.shadowUpdates > 0); ++i) await frames(1);
    if (!loaded.length) throw new Error("<PenumbraShadows> never loaded");
    await frames(5);
    const on = pixels();
    const shadows = loaded[0];
    setShadowsOn(false); // unmount: the effect's cleanup disposes the add-on
    await frames(10);
    const off = pixels();
    return {kind: "r3f", width: on.width, height: on.height, on: on.rgba, off: off.rgba, disposed: shadows.disposed,
            updates: shadows.info.shadowUpdates, library: "React Three Fiber"};
}

createRoot(document.getElementById("root")).render(<App />);
window.bundleCheck = {run: () => run().catch((e) => ({error: `${e.message}\n${e.stack}`})), materials: ["standard"]};
