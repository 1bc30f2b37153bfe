//! A small compute-pass helper shared by every kernel (pipeline from an assembled WGSL
//! source with the workgroup size as override constants, bind group, dispatch) and the one
//! readback routine that removes wgpu's row padding for every face and mip.

use crate::{Error, Result};

/// A compute pipeline plus its workgroup size.
pub struct ComputeKernel {
    label: &'static str,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    workgroup: [u32; 3],
}

/// Runs `f` inside a validation + out-of-memory error scope and turns a captured error into
/// [`Error::Gpu`].
pub fn with_error_scope<T>(device: &wgpu::Device, stage: &str, f: impl FnOnce() -> T) -> Result<T> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let out = f();
    let v = pollster::block_on(validation.pop());
    let o = pollster::block_on(oom.pop());
    match v.or(o) {
        Some(e) => Err(Error::Gpu {
            stage: stage.to_string(),
            message: e.to_string(),
        }),
        None => Ok(out),
    }
}

impl ComputeKernel {
    /// Compiles `source` (entry point `main`) with the given workgroup size, which the
    /// shader reads as the overrides `WORKGROUP_X/Y/Z`.
    pub fn new(
        device: &wgpu::Device,
        label: &'static str,
        source: &str,
        workgroup: [u32; 3],
    ) -> Result<Self> {
        Self::with_constants(device, label, source, workgroup, &[])
    }

    /// [`ComputeKernel::new`] with further pipeline-overridable constants of the shader.
    pub fn with_constants(
        device: &wgpu::Device,
        label: &'static str,
        source: &str,
        workgroup: [u32; 3],
        overrides: &[(&str, f64)],
    ) -> Result<Self> {
        with_error_scope(device, &format!("{label} pipeline"), || {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            let constants: Vec<(&str, f64)> = [
                ("WORKGROUP_X", workgroup[0] as f64),
                ("WORKGROUP_Y", workgroup[1] as f64),
                ("WORKGROUP_Z", workgroup[2] as f64),
            ]
            .into_iter()
            .chain(overrides.iter().copied())
            .collect();
            let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    zero_initialize_workgroup_memory: true,
                },
                cache: None,
            });
            let layout = pipeline.get_bind_group_layout(0);
            ComputeKernel {
                label,
                pipeline,
                layout,
                workgroup,
            }
        })
    }

    /// Records one dispatch covering `extent` invocations (rounded up to whole
    /// workgroups), with `resources` bound to group 0 at bindings 0, 1, 2, ...
    pub fn dispatch(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        resources: &[wgpu::BindingResource<'_>],
        extent: [u32; 3],
    ) {
        let bind_group = bind_group(device, Some(self.label), &self.layout, resources);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(
            extent[0].div_ceil(self.workgroup[0]),
            extent[1].div_ceil(self.workgroup[1]),
            extent[2].div_ceil(self.workgroup[2]),
        );
    }
}

/// A bind group of `layout` with `resources` at bindings 0, 1, 2, ...
pub fn bind_group(
    device: &wgpu::Device,
    label: Option<&str>,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: r.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label,
        layout,
        entries: &entries,
    })
}

/// A bind group of `layout` with each resource at the binding it names: for an entry point
/// that reads some of its module's bindings only (a pipeline's layout from its shader
/// holds the bindings its entry point reads).
pub fn bind_group_at(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    resources: &[(u32, wgpu::BindingResource<'_>)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .map(|(binding, r)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: r.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &entries,
    })
}

/// Creates a buffer initialised with `contents`.
pub fn buffer_with_data(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage,
    })
}

/// A storage buffer holding `data`. A storage binding cannot be empty, so an empty `data`
/// gets two zero vec4s (one hot texel's size) in its place; the kernels read none of them
/// because their count is 0.
pub fn storage_buffer<T: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    data: &[T],
) -> wgpu::Buffer {
    let placeholder = [0.0f32; 8];
    let bytes: &[u8] = if data.is_empty() {
        bytemuck::cast_slice(&placeholder)
    } else {
        bytemuck::cast_slice(data)
    };
    buffer_with_data(device, label, bytes, wgpu::BufferUsages::STORAGE)
}

/// A uniform buffer holding `value`.
pub fn uniform_buffer<T: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    value: &T,
) -> wgpu::Buffer {
    buffer_with_data(
        device,
        label,
        bytemuck::bytes_of(value),
        wgpu::BufferUsages::UNIFORM,
    )
}

/// Reads every array layer of one mip level of an `Rgba32Float` texture back to the CPU,
/// tightly packed: layer-major, then rows top to bottom, 4 floats per texel.
pub fn read_texture_level(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    mip_level: u32,
) -> Result<Vec<f32>> {
    if texture.format() != wgpu::TextureFormat::Rgba32Float {
        return Err(Error::Gpu {
            stage: "readback".into(),
            message: format!(
                "expected an Rgba32Float texture, got {:?}",
                texture.format()
            ),
        });
    }
    let bytes = read_texture_bytes(device, queue, texture, mip_level)?;
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}

/// Reads every array layer of one mip level of a texture of an uncompressed format back
/// to the CPU as bytes, tightly packed: layer-major, then rows top to bottom. wgpu pads
/// each row of the copy to 256 bytes; the padding is removed here.
pub fn read_texture_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    mip_level: u32,
) -> Result<Vec<u8>> {
    let texel_bytes = texture
        .format()
        .block_copy_size(None)
        .ok_or_else(|| Error::Gpu {
            stage: "readback".into(),
            message: format!("{:?} has no single copy size", texture.format()),
        })?;
    let width = (texture.width() >> mip_level).max(1);
    let height = (texture.height() >> mip_level).max(1);
    let layers = texture.depth_or_array_layers();
    let row_bytes = width * texel_bytes;
    let padded_row = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let size = padded_row as u64 * height as u64 * layers as u64;
    let staging = with_error_scope(device, "readback", || {
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
        );
        queue.submit([encoder.finish()]);
        staging
    })?;
    let bytes = map_read(device, &staging)?;
    let mut out = Vec::with_capacity((row_bytes * height * layers) as usize);
    for row in bytes.chunks_exact(padded_row as usize) {
        out.extend_from_slice(&row[..row_bytes as usize]);
    }
    Ok(out)
}

/// Maps a `MAP_READ` buffer whose copies have been submitted, waits for the GPU and
/// returns its bytes (the buffer is unmapped again).
pub fn map_read(device: &wgpu::Device, staging: &wgpu::Buffer) -> Result<Vec<u8>> {
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| Error::Gpu {
            stage: "readback".into(),
            message: e.to_string(),
        })?;
    rx.recv()
        .map_err(|e| e.to_string())
        .and_then(|r| r.map_err(|e| e.to_string()))
        .map_err(|message| Error::Gpu {
            stage: "readback map".into(),
            message,
        })?;
    let view = slice.get_mapped_range().map_err(|e| Error::Gpu {
        stage: "readback map".into(),
        message: e.to_string(),
    })?;
    let bytes = view.to_vec();
    drop(view);
    staging.unmap();
    Ok(bytes)
}
