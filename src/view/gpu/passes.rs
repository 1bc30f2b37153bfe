//! The viewer's GPU passes, recorded into a frame's command encoder: the forward pass,
//! the deferred G-buffer and split-sum passes, one truth estimate and the present pass
//! (what each computes: the parent module's docs and the shaders named there). The caller
//! records them inside its frame's error scope.

use crate::gpu::compute::{bind_group, bind_group_at};
use crate::gpu::preview::TruthUniform;
use crate::plan::shading::LightBrdf;
use crate::view::raster::FLOOR_VERTICES;
use crate::Result;

use super::{gpu_error, ForwardKey, GpuRenderer, LightTextures, Targets, MAX_TRUTH_POINTS};

/// A texture view as a binding.
fn view(v: &wgpu::TextureView) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::TextureView(v)
}

impl GpuRenderer {
    /// What every pass of a frame reads: the light, the model's vertices and the targets.
    pub(super) fn frame_inputs(&self) -> Result<(&LightTextures, (&wgpu::Buffer, u32), &Targets)> {
        match (&self.light, &self.vertices, &self.targets) {
            (Some(light), Some((vertices, count)), Some(t)) => Ok((light, (vertices, *count), t)),
            _ => Err(gpu_error("viewer frame", "no light or model uploaded")),
        }
    }

    /// The model (and the ray-cast sphere) drawn into an open pass by `mesh` and `sphere`:
    /// the sphere first, then the model and, with `floor`, the floor
    /// (`raster::scene_vertices`), nearer surfaces before the floor, so that what they
    /// hide is not shaded.
    fn draw_scene(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        (mesh, sphere): (&wgpu::RenderPipeline, &wgpu::RenderPipeline),
        resources: &[wgpu::BindingResource],
        floor: bool,
    ) -> Result<()> {
        let (_, (vertices, count), _) = self.frame_inputs()?;
        let bind = |pipeline: &wgpu::RenderPipeline| {
            bind_group(
                &self.device,
                None,
                &pipeline.get_bind_group_layout(0),
                resources,
            )
        };
        if self.sphere {
            pass.set_pipeline(sphere);
            pass.set_bind_group(0, &bind(sphere), &[]);
            pass.set_vertex_buffer(0, self.sphere_box.slice(..));
            pass.draw(0..36, 0..1);
        }
        pass.set_pipeline(mesh);
        pass.set_bind_group(0, &bind(mesh), &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.draw(0..if floor { count } else { count - FLOOR_VERTICES }, 0..1);
        Ok(())
    }

    /// The forward pass: the object's G-buffer (its pixels' position and normal, the
    /// G-buffer pass's pipelines drawing the object alone), then the object shaded from it
    /// by one triangle over the frame drawn where a surface left its depth, so that each of
    /// its pixels is shaded once, in full blocks of a software rasteriser's lanes, where its
    /// small triangles would leave most lanes idle and be shaded again where they overlap;
    /// then the floor from its caches and the background, each displayed.
    pub(super) fn encode_forward(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        (target, key): (&wgpu::TextureView, ForwardKey),
    ) -> Result<()> {
        let (light, (vertices, count), t) = self.frame_inputs()?;
        let p = self.compiled_display(key.format)?;
        let surfaces = self.compiled_forward(key)?;
        let hud = t.hud.create_view(&Default::default());
        {
            let mut pass = begin_pass(
                encoder,
                "view object gbuffer",
                &[kept(&t.position), kept(&t.normal)],
                Some((&t.depth, true)),
            );
            self.draw_scene(
                &mut pass,
                (&self.mesh_pipeline, &self.sphere_pipeline),
                &[self.frame.as_entire_binding()],
                false,
            )?;
        }
        let object_group = bind_group_at(
            &self.device,
            &surfaces.object.get_bind_group_layout(0),
            &[
                (0, self.frame.as_entire_binding()),
                (1, light.split_sum.as_entire_binding()),
                (2, view(&light.specular)),
                (3, self.present.as_entire_binding()),
                (4, view(&hud)),
                (5, wgpu::BindingResource::Sampler(&self.cube_linear)),
                (6, view(&light.irradiance)),
                (7, view(&light.lut)),
                (8, self.lights.as_entire_binding()),
                (9, light.sun_texels.as_entire_binding()),
                (10, view(&self.shadow)),
                (13, view(&t.position)),
                (14, view(&t.normal)),
            ],
        );
        // The floor's fragments read the frame, the display's block and the HUD, the point
        // lights, the floor's table and its shadows through the sampler (and the grid's
        // header from storage) alone.
        let floor_group = bind_group_at(
            &self.device,
            &surfaces.floor.get_bind_group_layout(0),
            &[
                (0, self.frame.as_entire_binding()),
                (3, self.present.as_entire_binding()),
                (4, view(&hud)),
                (5, wgpu::BindingResource::Sampler(&self.cube_linear)),
                (8, self.lights.as_entire_binding()),
                (12, self.floor_shadow.as_entire_binding()),
                (15, view(&self.floor_table_texels)),
                (16, view(&self.floor_shadow_texels)),
                (17, wgpu::BindingResource::Sampler(&self.floor_repeat)),
            ],
        );
        let background_group = bind_group(
            &self.device,
            None,
            &p.background.get_bind_group_layout(0),
            &[
                self.frame.as_entire_binding(),
                light.split_sum.as_entire_binding(),
                view(&light.specular),
                self.present.as_entire_binding(),
                view(&hud),
                wgpu::BindingResource::Sampler(&self.cube_linear),
            ],
        );
        let mut pass = begin_pass(
            encoder,
            "view forward",
            &[cleared(target)],
            Some((&t.depth, false)),
        );
        pass.set_pipeline(&surfaces.object);
        pass.set_bind_group(0, &object_group, &[]);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&surfaces.floor);
        pass.set_bind_group(0, &floor_group, &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.draw(count - FLOOR_VERTICES..count, 0..1);
        pass.set_pipeline(&p.background);
        pass.set_bind_group(0, &background_group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// The G-buffer pass, then the split-sum kernel into the split-sum buffer.
    pub(super) fn encode_deferred_split_sum(
        &self,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<()> {
        let (light, _, t) = self.frame_inputs()?;
        {
            let mut pass = begin_pass(
                encoder,
                "view gbuffer",
                &[cleared(&t.position), cleared(&t.normal)],
                Some((&t.depth, true)),
            );
            let drawn = self.draw_scene(
                &mut pass,
                (&self.mesh_pipeline, &self.sphere_pipeline),
                &[self.frame.as_entire_binding()],
                true,
            );
            drop(pass);
            self.split_sum.dispatch(
                &self.device,
                encoder,
                &[
                    self.frame.as_entire_binding(),
                    light.split_sum.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&light.specular),
                    wgpu::BindingResource::TextureView(&light.irradiance),
                    wgpu::BindingResource::TextureView(&light.lut),
                    self.lights.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&t.position),
                    wgpu::BindingResource::TextureView(&t.normal),
                    t.shaded.as_entire_binding(),
                    light.sun_texels.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&self.shadow),
                    self.floor.as_entire_binding(),
                    self.floor_shadow.as_entire_binding(),
                ],
                [t.size.0, t.size.1, 1],
            );
            drawn
        }
    }

    /// One truth estimate with `points` added to the truth buffer.
    pub(super) fn encode_truth(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        points: &[[f32; 4]],
    ) -> Result<()> {
        let (light, _, t) = self.frame_inputs()?;
        {
            let n = points.len().min(MAX_TRUTH_POINTS as usize);
            self.queue
                .write_buffer(&self.points, 0, bytemuck::cast_slice(&points[..n]));
            let params = TruthUniform {
                env_size: light.truth_env_size,
                hot_count: light.hot_count,
                point_count: n as u32,
                // The recipe's BRDF, uncompensated (the viewer's truth binds no LUT).
                masking: LightBrdf::GENERIC.masking as u32,
                diffuse: LightBrdf::GENERIC.diffuse as u32,
                compensated: 0,
                lut_width: 0,
                lut_height: 0,
            };
            self.queue
                .write_buffer(&self.truth_params, 0, bytemuck::bytes_of(&params));
            self.truth.dispatch(
                &self.device,
                encoder,
                &[
                    self.frame.as_entire_binding(),
                    self.truth_params.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&light.env),
                    wgpu::BindingResource::TextureView(&light.cold),
                    light.hot.as_entire_binding(),
                    self.points.as_entire_binding(),
                    self.lights.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&t.position),
                    wgpu::BindingResource::TextureView(&t.normal),
                    t.accum.as_entire_binding(),
                    light.sun_texels.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&self.shadow),
                    self.floor_shadow.as_entire_binding(),
                ],
                [t.size.0, t.size.1, 1],
            );
        }
        Ok(())
    }

    /// The present pass: the mode's picture from the per-pixel buffers, with the HUD.
    pub(super) fn encode_present(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        (target, format): (&wgpu::TextureView, wgpu::TextureFormat),
    ) -> Result<()> {
        let (_, _, t) = self.frame_inputs()?;
        let p = self.compiled_display(format)?;
        {
            let hud = t.hud.create_view(&Default::default());
            let group = bind_group(
                &self.device,
                None,
                &p.present.get_bind_group_layout(0),
                &[
                    self.present.as_entire_binding(),
                    t.shaded.as_entire_binding(),
                    t.accum.as_entire_binding(),
                    self.heat.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&hud),
                ],
            );
            let mut pass = begin_pass(encoder, "view present", &[cleared(target)], None);
            pass.set_pipeline(&p.present);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        Ok(())
    }
}

/// A colour attachment loaded with `load` and stored.
fn colour_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        resolve_target: None,
        ops: wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        },
        depth_slice: None,
    })
}

/// A colour attachment cleared to transparent black.
fn cleared(view: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    colour_attachment(view, wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT))
}

/// A colour attachment kept as it is: a target whose pixels the pass does not cover are
/// not read afterwards.
fn kept(view: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    colour_attachment(view, wgpu::LoadOp::Load)
}

/// A render pass into `colours` and `depth` when given: (its view, whether it is cleared
/// to 1, the far plane, or kept as an earlier pass left it).
fn begin_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    colours: &[Option<wgpu::RenderPassColorAttachment<'_>>],
    depth: Option<(&wgpu::TextureView, bool)>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: colours,
        depth_stencil_attachment: depth.map(|(view, clear)| {
            wgpu::RenderPassDepthStencilAttachment {
                view,
                depth_ops: Some(wgpu::Operations {
                    load: if clear {
                        wgpu::LoadOp::Clear(1.0)
                    } else {
                        wgpu::LoadOp::Load
                    },
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
