//! Arm's astc-encoder 5.3.0 (Apache-2.0, vendored under `astc-encoder/`), compiled by
//! `build.rs`, and a safe binding of the part splitsum uses: HDR compression of 2D RGBA
//! `f32` images at any 2D block footprint, on several threads sharing one context as
//! astcenc's API allows (`astcenc_compress_image` called once per thread index, then
//! `astcenc_compress_reset`), and the library's own decompression.
//!
//! The declarations below are written by hand from `astcenc.h` (no bindgen, so a build needs
//! no libclang); [`Context::hdr`] refuses to run when their sizes disagree with the compiled
//! header's (`src/layout.cpp`).

use std::ffi::{c_char, c_void, CStr};
use std::fmt;
use std::ptr::NonNull;

mod ffi {
    use std::ffi::{c_char, c_void};

    /// `astcenc_profile::ASTCENC_PRF_HDR`: HDR RGB and HDR alpha.
    pub const PRF_HDR: u32 = 3;
    /// `astcenc_type::ASTCENC_TYPE_F32`.
    pub const TYPE_F32: u32 = 2;
    /// `astcenc_error::ASTCENC_SUCCESS`.
    pub const SUCCESS: u32 = 0;
    /// `astcenc_swz` selectors.
    pub const SWZ_R: u32 = 0;
    pub const SWZ_G: u32 = 1;
    pub const SWZ_B: u32 = 2;
    pub const SWZ_A: u32 = 3;

    #[repr(C)]
    pub struct Context {
        _opaque: [u8; 0],
    }

    #[repr(C)]
    #[derive(Clone, Copy)]
    pub struct Config {
        pub profile: u32,
        pub flags: u32,
        pub block_x: u32,
        pub block_y: u32,
        pub block_z: u32,
        pub cw_r_weight: f32,
        pub cw_g_weight: f32,
        pub cw_b_weight: f32,
        pub cw_a_weight: f32,
        pub a_scale_radius: u32,
        pub rgbm_m_scale: f32,
        pub tune_partition_count_limit: u32,
        pub tune_2partition_index_limit: u32,
        pub tune_3partition_index_limit: u32,
        pub tune_4partition_index_limit: u32,
        pub tune_block_mode_limit: u32,
        pub tune_refinement_limit: u32,
        pub tune_candidate_limit: u32,
        pub tune_2partitioning_candidate_limit: u32,
        pub tune_3partitioning_candidate_limit: u32,
        pub tune_4partitioning_candidate_limit: u32,
        pub tune_db_limit: f32,
        pub tune_mse_overshoot: f32,
        pub tune_2partition_early_out_limit_factor: f32,
        pub tune_3partition_early_out_limit_factor: f32,
        pub tune_2plane_early_out_limit_correlation: f32,
        pub tune_search_mode0_enable: f32,
        pub progress_callback: Option<extern "C" fn(f32)>,
    }

    #[repr(C)]
    pub struct Image {
        pub dim_x: u32,
        pub dim_y: u32,
        pub dim_z: u32,
        pub data_type: u32,
        pub data: *mut *mut c_void,
    }

    #[repr(C)]
    pub struct Swizzle {
        pub r: u32,
        pub g: u32,
        pub b: u32,
        pub a: u32,
    }

    extern "C" {
        pub fn astcenc_config_init(
            profile: u32,
            block_x: u32,
            block_y: u32,
            block_z: u32,
            quality: f32,
            flags: u32,
            config: *mut Config,
        ) -> u32;
        pub fn astcenc_context_alloc(
            config: *const Config,
            thread_count: u32,
            context: *mut *mut Context,
        ) -> u32;
        pub fn astcenc_compress_image(
            context: *mut Context,
            image: *mut Image,
            swizzle: *const Swizzle,
            data_out: *mut u8,
            data_len: usize,
            thread_index: u32,
        ) -> u32;
        pub fn astcenc_compress_reset(context: *mut Context) -> u32;
        pub fn astcenc_decompress_image(
            context: *mut Context,
            data: *const u8,
            data_len: usize,
            image_out: *mut Image,
            swizzle: *const Swizzle,
            thread_index: u32,
        ) -> u32;
        pub fn astcenc_decompress_reset(context: *mut Context) -> u32;
        pub fn astcenc_context_free(context: *mut Context);
        pub fn astcenc_get_error_string(status: u32) -> *const c_char;

        pub fn splitsum_astcenc_config_size() -> usize;
        pub fn splitsum_astcenc_config_callback_offset() -> usize;
        pub fn splitsum_astcenc_image_size() -> usize;
        pub fn splitsum_astcenc_swizzle_size() -> usize;
    }
}

/// Bytes of one ASTC block, whatever its footprint.
pub const BLOCK_BYTES: usize = 16;

/// astcenc's search presets (`ASTCENC_PRE_*` in `astcenc.h`): how much of the encoding space
/// it searches, from fastest to best.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// `ASTCENC_PRE_FASTEST` (0).
    Fastest,
    /// `ASTCENC_PRE_FAST` (10).
    Fast,
    /// `ASTCENC_PRE_MEDIUM` (60).
    Medium,
    /// `ASTCENC_PRE_THOROUGH` (98).
    Thorough,
    /// `ASTCENC_PRE_VERYTHOROUGH` (99).
    VeryThorough,
    /// `ASTCENC_PRE_EXHAUSTIVE` (100).
    Exhaustive,
}

impl Preset {
    /// The quality value `astcenc_config_init` takes for the preset (`astcenc.h`).
    pub fn quality(self) -> f32 {
        match self {
            Preset::Fastest => 0.0,
            Preset::Fast => 10.0,
            Preset::Medium => 60.0,
            Preset::Thorough => 98.0,
            Preset::VeryThorough => 99.0,
            Preset::Exhaustive => 100.0,
        }
    }
}

/// An astcenc call that failed: the function and astcenc's own message for its status.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// The astcenc function (or the binding's check) that failed.
    pub call: &'static str,
    /// astcenc's message (`astcenc_get_error_string`), or the binding's.
    pub message: String,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.call, self.message)
    }
}

impl std::error::Error for Error {}

fn check(call: &'static str, status: u32) -> Result<(), Error> {
    if status == ffi::SUCCESS {
        return Ok(());
    }
    // SAFETY: astcenc_get_error_string returns a static NUL-terminated string or null.
    let text: *const c_char = unsafe { ffi::astcenc_get_error_string(status) };
    let message = if text.is_null() {
        format!("status {status}")
    } else {
        // SAFETY: non-null, static and NUL-terminated (astcenc_entry.cpp).
        unsafe { CStr::from_ptr(text) }
            .to_string_lossy()
            .into_owned()
    };
    Err(Error { call, message })
}

/// Whether the binding's declarations have the sizes the compiled `astcenc.h` gives them.
pub fn layout_matches() -> bool {
    // SAFETY: the shim's functions take nothing and return sizes.
    unsafe {
        ffi::splitsum_astcenc_config_size() == std::mem::size_of::<ffi::Config>()
            && ffi::splitsum_astcenc_config_callback_offset()
                == std::mem::offset_of!(ffi::Config, progress_callback)
            && ffi::splitsum_astcenc_image_size() == std::mem::size_of::<ffi::Image>()
            && ffi::splitsum_astcenc_swizzle_size() == std::mem::size_of::<ffi::Swizzle>()
    }
}

/// The identity swizzle: RGBA in, RGBA out.
const IDENTITY: ffi::Swizzle = ffi::Swizzle {
    r: ffi::SWZ_R,
    g: ffi::SWZ_G,
    b: ffi::SWZ_B,
    a: ffi::SWZ_A,
};

/// An astcenc context for the HDR RGBA profile at one 2D block footprint, with a number of
/// worker threads. One image is compressed (or decompressed) at a time, hence `&mut self`.
pub struct Context {
    raw: NonNull<ffi::Context>,
    threads: u32,
    block: (u32, u32),
}

// SAFETY: the context is only used through `&mut self`, and astcenc allows a context to be
// used from any thread; within one call, several threads share it as its API documents.
unsafe impl Send for Context {}

/// A raw pointer handed to the worker threads of one call.
#[derive(Clone, Copy)]
struct Shared<T>(T);
// SAFETY: used only for the astcenc context and buffers of one call, which outlive its
// scoped threads; astcenc synchronises the threads' work on them.
unsafe impl<T> Send for Shared<T> {}
unsafe impl<T> Sync for Shared<T> {}

impl Context {
    /// A context for HDR RGBA (`ASTCENC_PRF_HDR`) at `block_x`×`block_y` texels a block, the
    /// search `preset`, and `threads` workers (at least one), every channel's error weighted
    /// alike.
    pub fn hdr(block_x: u32, block_y: u32, preset: Preset, threads: u32) -> Result<Context, Error> {
        Self::hdr_weighted(block_x, block_y, preset, threads, [1.0; 4])
    }

    /// [`Context::hdr`] with the encoder's error weighted per channel (RGBA; astcenc's
    /// `cw_*_weight`, 1 each by default).
    pub fn hdr_weighted(
        block_x: u32,
        block_y: u32,
        preset: Preset,
        threads: u32,
        weights: [f32; 4],
    ) -> Result<Context, Error> {
        if !layout_matches() {
            return Err(Error {
                call: "splitsum-astcenc",
                message: "the binding's structures disagree with the compiled astcenc.h".into(),
            });
        }
        let threads = threads.max(1);
        let mut config = std::mem::MaybeUninit::<ffi::Config>::zeroed();
        // SAFETY: config points at writable memory of the header's size (layout checked).
        check("astcenc_config_init", unsafe {
            ffi::astcenc_config_init(
                ffi::PRF_HDR,
                block_x,
                block_y,
                1,
                preset.quality(),
                0,
                config.as_mut_ptr(),
            )
        })?;
        // SAFETY: astcenc_config_init succeeded and wrote every field.
        let mut config = unsafe { config.assume_init() };
        [
            config.cw_r_weight,
            config.cw_g_weight,
            config.cw_b_weight,
            config.cw_a_weight,
        ] = weights;
        let mut raw = std::ptr::null_mut();
        // SAFETY: config is initialised; raw receives the context.
        check("astcenc_context_alloc", unsafe {
            ffi::astcenc_context_alloc(&config, threads, &mut raw)
        })?;
        let raw = NonNull::new(raw).ok_or(Error {
            call: "astcenc_context_alloc",
            message: "returned no context".into(),
        })?;
        Ok(Context {
            raw,
            threads,
            block: (block_x, block_y),
        })
    }

    /// The block footprint, texels wide and high.
    pub fn block(&self) -> (u32, u32) {
        self.block
    }

    /// Bytes of the blocks of a `width`×`height` image: one block per started footprint.
    pub fn compressed_len(&self, width: u32, height: u32) -> usize {
        width.div_ceil(self.block.0) as usize * height.div_ceil(self.block.1) as usize * BLOCK_BYTES
    }

    /// Compresses a `width`×`height` image of RGBA texels (row-major) into row-major blocks.
    pub fn compress(
        &mut self,
        width: u32,
        height: u32,
        rgba: &[[f32; 4]],
    ) -> Result<Vec<u8>, Error> {
        Self::check_texels(width, height, rgba.len())?;
        let mut out = vec![0u8; self.compressed_len(width, height)];
        let mut plane = rgba.as_ptr() as *mut c_void;
        let mut image = ffi::Image {
            dim_x: width,
            dim_y: height,
            dim_z: 1,
            data_type: ffi::TYPE_F32,
            data: &mut plane,
        };
        let (ctx, img, dst, len) = (
            Shared(self.raw.as_ptr()),
            Shared(&mut image as *mut ffi::Image),
            Shared(out.as_mut_ptr()),
            out.len(),
        );
        let status = self.on_threads(move |index| {
            let (ctx, img, dst) = (ctx, img, dst);
            // SAFETY: the context, image (read only by astcenc) and output outlive the call;
            // each thread passes its own index, as astcenc_compress_image requires.
            unsafe { ffi::astcenc_compress_image(ctx.0, img.0, &IDENTITY, dst.0, len, index) }
        });
        // SAFETY: every thread of the call has returned.
        let reset = unsafe { ffi::astcenc_compress_reset(self.raw.as_ptr()) };
        check("astcenc_compress_image", status)?;
        check("astcenc_compress_reset", reset)?;
        Ok(out)
    }

    /// Astcenc's own decode of `blocks` (a `width`×`height` image's row-major blocks) to RGBA
    /// `f32` texels, row-major.
    pub fn decompress(
        &mut self,
        width: u32,
        height: u32,
        blocks: &[u8],
    ) -> Result<Vec<[f32; 4]>, Error> {
        if blocks.len() != self.compressed_len(width, height) {
            return Err(Error {
                call: "splitsum-astcenc",
                message: format!(
                    "{} bytes for a {width}x{height} image of {}x{} blocks, which needs {}",
                    blocks.len(),
                    self.block.0,
                    self.block.1,
                    self.compressed_len(width, height)
                ),
            });
        }
        let mut texels = vec![[0.0f32; 4]; width as usize * height as usize];
        let mut plane = texels.as_mut_ptr() as *mut c_void;
        let mut image = ffi::Image {
            dim_x: width,
            dim_y: height,
            dim_z: 1,
            data_type: ffi::TYPE_F32,
            data: &mut plane,
        };
        let (ctx, img, src, len) = (
            Shared(self.raw.as_ptr()),
            Shared(&mut image as *mut ffi::Image),
            Shared(blocks.as_ptr()),
            blocks.len(),
        );
        let status = self.on_threads(move |index| {
            let (ctx, img, src) = (ctx, img, src);
            // SAFETY: as in compress; astcenc writes each texel of the image from one thread.
            unsafe { ffi::astcenc_decompress_image(ctx.0, src.0, len, img.0, &IDENTITY, index) }
        });
        // SAFETY: every thread of the call has returned.
        let reset = unsafe { ffi::astcenc_decompress_reset(self.raw.as_ptr()) };
        check("astcenc_decompress_image", status)?;
        check("astcenc_decompress_reset", reset)?;
        Ok(texels)
    }

    /// Runs `work(thread_index)` on every thread index of the context at once, returning the
    /// first failing status (or success).
    fn on_threads(&self, work: impl Fn(u32) -> u32 + Sync) -> u32 {
        let work = &work;
        std::thread::scope(|scope| {
            let others: Vec<_> = (1..self.threads)
                .map(|index| scope.spawn(move || work(index)))
                .collect();
            let mut status = work(0);
            for handle in others {
                // A worker only returns astcenc's status; it cannot panic.
                let other = handle.join().unwrap_or(u32::MAX);
                if status == ffi::SUCCESS {
                    status = other;
                }
            }
            status
        })
    }

    fn check_texels(width: u32, height: u32, len: usize) -> Result<(), Error> {
        if width == 0 || height == 0 || len != width as usize * height as usize {
            return Err(Error {
                call: "splitsum-astcenc",
                message: format!("{len} texels for a {width}x{height} image"),
            });
        }
        Ok(())
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        // SAFETY: the context was allocated by astcenc_context_alloc and is freed once.
        unsafe { ffi::astcenc_context_free(self.raw.as_ptr()) }
    }
}
