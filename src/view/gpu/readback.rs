//! Reading the viewer's frames back: the HDR buffers (for tests) and an offscreen picture.

use image::RgbaImage;

use crate::gpu::compute::{map_read, read_texture_bytes};
use crate::gpu::texture::create_texture_2d;
use crate::view::frame::{FrameUniform, HdrFrame, PresentUniform};
use crate::Result;

use super::pipelines::buffer;
use super::{gpu_error, GpuRenderer};

impl GpuRenderer {
    /// The last frame's split-sum (radiance, surface id) and truth accumulation
    /// (radiance × points, points) per pixel; a frame drawn by the forward pass gets its
    /// split-sum from the deferred passes first.
    pub fn read_hdr(&mut self) -> Result<HdrFrame> {
        self.update_deferred()?;
        let t = self
            .targets
            .as_ref()
            .ok_or_else(|| gpu_error("viewer readback", "nothing rendered"))?;
        let read = |src: &wgpu::Buffer| -> Result<Vec<[f32; 4]>> {
            let staging = buffer(
                &self.device,
                "view readback",
                src.size(),
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            );
            let mut encoder = self.device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(src, 0, &staging, 0, src.size());
            self.queue.submit([encoder.finish()]);
            let bytes = map_read(&self.device, &staging)?;
            Ok(bytemuck::pod_collect_to_vec(&bytes))
        };
        Ok((read(&t.shaded)?, read(&t.accum)?))
    }

    /// Renders into a new `Rgba8Unorm` texture and reads the picture back.
    pub fn render_image(
        &mut self,
        frame: &FrameUniform,
        present: &PresentUniform,
        geometry_changed: bool,
        points: Option<&[[f32; 4]]>,
        hud: Option<&RgbaImage>,
    ) -> Result<RgbaImage> {
        let (w, h) = (frame.width, frame.height);
        let texture = create_texture_2d(
            &self.device,
            "view offscreen",
            (w, h, 1),
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&Default::default());
        let target = (&view, wgpu::TextureFormat::Rgba8Unorm);
        self.render(frame, present, geometry_changed, points, hud, target)?;
        let pixels = read_texture_bytes(&self.device, &self.queue, &texture, 0)?;
        RgbaImage::from_raw(w, h, pixels)
            .ok_or_else(|| gpu_error("viewer readback", "short picture"))
    }
}
