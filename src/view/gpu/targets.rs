//! The viewer's per-size targets: the G-buffer (position and normal, depth), the
//! deferred path's per-pixel buffers and the HUD's texture, made again when the frame's
//! size changes.

use image::RgbaImage;

use crate::gpu::compute::with_error_scope;
use crate::gpu::texture::{create_texture_2d, write_texels};
use crate::Result;

use super::pipelines::buffer;
use super::{gpu_error, GpuRenderer, DEPTH_FORMAT, GBUFFER_FORMAT};

/// The per-size targets.
pub(super) struct Targets {
    pub(super) size: (u32, u32),
    pub(super) position: wgpu::TextureView,
    pub(super) normal: wgpu::TextureView,
    pub(super) depth: wgpu::TextureView,
    pub(super) shaded: wgpu::Buffer,
    pub(super) accum: wgpu::Buffer,
    pub(super) hud: wgpu::Texture,
}

impl GpuRenderer {
    /// The targets of a `size` frame, made again when the size is new.
    pub(super) fn targets(&mut self, size: (u32, u32)) -> Result<&Targets> {
        if self.targets.as_ref().map(|t| t.size) != Some(size) {
            let device = &self.device;
            let texture = |label: &str, format: wgpu::TextureFormat, usage: wgpu::TextureUsages| {
                create_texture_2d(device, label, (size.0, size.1, 1), format, usage)
            };
            let pixels = size.0 as u64 * size.1 as u64;
            let gusage =
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
            let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
            let targets = with_error_scope(device, "creating the viewer's targets", || Targets {
                size,
                position: texture("view position", GBUFFER_FORMAT, gusage)
                    .create_view(&Default::default()),
                normal: texture("view normal", GBUFFER_FORMAT, gusage)
                    .create_view(&Default::default()),
                depth: texture(
                    "view depth",
                    DEPTH_FORMAT,
                    wgpu::TextureUsages::RENDER_ATTACHMENT,
                )
                .create_view(&Default::default()),
                shaded: buffer(device, "view shaded", 16 * pixels, storage),
                accum: buffer(device, "view accum", 16 * pixels, storage),
                hud: texture(
                    "view hud",
                    wgpu::TextureFormat::Rgba8Unorm,
                    wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                ),
            })?;
            self.targets = Some(targets);
        }
        self.targets
            .as_ref()
            .ok_or_else(|| gpu_error("viewer targets", "missing"))
    }

    /// Uploads a new HUD image of a `size` frame.
    pub(super) fn upload_hud(&self, image: &RgbaImage, size: (u32, u32)) {
        let Some(t) = &self.targets else { return };
        write_texels(
            &self.queue,
            &t.hud,
            (0, 0),
            (size.0, size.1, 1),
            image.as_raw(),
        );
    }
}
