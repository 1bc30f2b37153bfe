// Draws `view` until two frames have been drawn (the first may still use textures whose
// uploads it issues). Filament's web build is single-threaded: `engine.execute()` runs a
// frame's commands, and `beginFrame` skips frames until the GPU fences of earlier ones
// signal, which WebGL lets happen only between tasks, so the loop yields to the event loop
// between frames. Shared by check.js and the README recipe's page (check.mjs).
export async function drawFrames(engine, renderer, swapChain, view) {
  let drawn = 0;
  for (let tries = 0; drawn < 2; tries++) {
    if (tries > 200) throw new Error('Filament skipped every frame');
    if (renderer.beginFrame(swapChain)) {
      renderer.renderView(view);
      renderer.endFrame();
      drawn++;
    }
    engine.execute();
    if (drawn < 2) await new Promise((ok) => setTimeout(ok, 0));
  }
}
