// usePenumbraShadows.js — penumbra-three in React Three Fiber: a hook and a component that give a
// light Penumbra's soft shadows with the lifecycle React expects: the add-on is loaded in an
// effect (again when the renderer, the scene, the light or the options change), disposed when the
// component unmounts, and updated in useFrame before R3F renders the frame.
//
//   const light = useRef();
//   <rectAreaLight ref={light} ... />
//   <PenumbraShadows light={light} emission="rect-nbuffer-16x512" />   // or usePenumbraShadows(light, options)
//
// RectAreaLight needs RectAreaLightUniformsLib.init() once (three's rule), before the first frame.
import {useEffect, useState} from "react";
import {useFrame, useThree} from "@react-three/fiber";
import {PenumbraShadows as Shadows} from "penumbra-three";

// Returns the add-on (null until it has loaded). `options` as PenumbraShadows.load's; compared by
// value, so an inline object does not reload it every render.
export function usePenumbraShadows(lightRef, options = {}) {
    const gl = useThree((state) => state.gl);
    const scene = useThree((state) => state.scene);
    const [shadows, setShadows] = useState(null);
    const key = JSON.stringify(options);
    useEffect(() => {
        if (!lightRef.current) return undefined;
        let unmounted = false, loaded = null;
        Shadows.load(gl, scene, lightRef.current, JSON.parse(key)).then((s) => {
            if (unmounted) return s.dispose(); // unmounted while loading
            loaded = s;
            setShadows(s);
            return null;
        }, (e) => console.error(e));
        return () => {
            unmounted = true;
            if (loaded) loaded.dispose();
            setShadows(null);
        };
    }, [gl, scene, lightRef, key]);
    // (a negative priority runs before R3F's own render, and leaves rendering to it)
    useFrame(() => {
        if (shadows && !shadows.disposed) shadows.update();
    }, -1);
    return shadows;
}

// The same as a component: <PenumbraShadows light={ref} {...options} onLoad={(shadows) => …} />.
export function PenumbraShadows({light, onLoad, ...options}) {
    const shadows = usePenumbraShadows(light, options);
    useEffect(() => {
        if (shadows && onLoad) onLoad(shadows);
    }, [shadows, onLoad]);
    return null;
}

