// offscreen_canvas.mjs — for pages on Babylon's WebGPUEngine in headless Chromium (babylon_test.mjs,
// babylon_package_test.mjs): there, with WebGPU on SwiftShader, presenting a WebGPU canvas loses
// the device ("Could not find SharedImageBackingFactory ... WebgpuSwapChainTexture": the swap
// chain's shared image cannot be made; three.js's tests render to render targets and never hit it).
// installOffscreenCanvas, run in the page before its scripts (page.evaluateOnNewDocument), makes
// every "webgpu" context of a canvas one whose current texture is a plain GPUTexture of the
// canvas's size: the engine renders its frames there as it would to the canvas, nothing is
// presented, and window.penumbraOffscreenCanvas.read(canvas) reads the last frame back.

// (self-contained: puppeteer serializes it into the page)
export function installOffscreenCanvas() {
    const frames = new WeakMap(); // canvas → {texture, device}
    const original = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (type, ...rest) {
        if (type !== "webgpu") return original.call(this, type, ...rest);
        const canvas = this;
        let config = null;
        const drop = () => {
            frames.get(canvas)?.texture.destroy();
            frames.delete(canvas);
        };
        return {
            canvas,
            configure(c) {
                drop();
                config = c;
            },
            unconfigure() {
                drop();
                config = null;
            },
            getConfiguration: () => config,
            getCurrentTexture() {
                let frame = frames.get(canvas);
                if (!frame || frame.texture.width !== canvas.width || frame.texture.height !== canvas.height) {
                    drop();
                    const texture = config.device.createTexture({label: "offscreen canvas", size: [canvas.width, canvas.height], format: config.format,
                                                                 usage: config.usage | GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC});
                    frames.set(canvas, (frame = {texture, device: config.device}));
                }
                return frame.texture;
            },
        };
    };
    // The canvas's last frame as RGBA bytes, top row first (as a 2D canvas's getImageData).
    const read = async (canvas) => {
        const frame = frames.get(canvas);
        if (!frame) throw new Error("the canvas has no WebGPU frame");
        const {texture, device} = frame;
        const width = texture.width, height = texture.height, bytesPerRow = Math.ceil((4 * width) / 256) * 256;
        const buffer = device.createBuffer({size: bytesPerRow * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ});
        const encoder = device.createCommandEncoder();
        encoder.copyTextureToBuffer({texture}, {buffer, bytesPerRow}, [width, height, 1]);
        device.queue.submit([encoder.finish()]);
        await buffer.mapAsync(GPUMapMode.READ);
        const bytes = new Uint8Array(buffer.getMappedRange());
        const out = new Uint8ClampedArray(4 * width * height);
        const bgra = texture.format.startsWith("bgra");
        for (let y = 0; y < height; ++y)
            for (let x = 0; x < width; ++x) {
                const i = y * bytesPerRow + 4 * x, o = 4 * (y * width + x);
                out[o] = bytes[i + (bgra ? 2 : 0)];
                out[o + 1] = bytes[i + 1];
                out[o + 2] = bytes[i + (bgra ? 0 : 2)];
                out[o + 3] = 255;
            }
        buffer.unmap();
        buffer.destroy();
        return out;
    };
    window.penumbraOffscreenCanvas = {read};
}
