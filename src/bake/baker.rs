//! [`Baker`]: the library's front door. It validates the options, opens the backend they
//! name, computes each target's LUTs once, and bakes inputs with the fallback policy of
//! the command line: with [`BackendChoice::Auto`], no adapter means the CPU backend (with
//! a note), and a GPU failure during an input (device lost, out of memory, a driver error)
//! redoes that input on the CPU backend, the LUTs included, with a warning, so the files
//! are exactly a CPU bake's, as the manifest says.

use std::path::Path;
use std::sync::Arc;

use crate::backend::{
    create_backend, shared_ltc_table, Backend, BackendChoice, BackendJob, CpuBackend,
};
use crate::bake::{bake, bake_environment, BakeOptions, BakeReport};
use crate::environment::sun::SunMode;
use crate::environment::{Cubemap, Environment};
use crate::io::cubemap::{clip_warning, write_cubemap_with, Container, CubeWriteOptions};
use crate::io::input::{load_faces, load_input, InputOptions, LoadedEnvironment};
use crate::plan::ltc::{ltc_brdf, LtcTable};
use crate::plan::lut::{BrdfLut, LutModel, DEFAULT_LUT_SIZE};
use crate::plan::shading::LightBrdf;
use crate::stages::convert::{default_cube_size, environment_into_cube};
use crate::stages::light::{BakedEnvironment, Stage};
use crate::stages::preview::{preview_baked, Preview, PreviewOptions};
use crate::{Error, Result};

/// An environment read from a file, with the warnings its reading raised (replaced
/// non-finite or negative values, an LDR image, …).
pub type LoadedInput = LoadedEnvironment;

/// Bakes environments as its [`BakeOptions`] say, on the backend they name.
///
/// ```no_run
/// use splitsum::{BakeOptions, Baker, GLTF};
/// let mut baker = Baker::new(BakeOptions::for_target(&GLTF))?;
/// let report = baker.bake("sky.hdr".as_ref(), "out".as_ref())?;
/// println!("{} files in {}", report.outputs.len(), report.out_dir.display());
/// # Ok::<(), splitsum::Error>(())
/// ```
pub struct Baker {
    opts: BakeOptions,
    backend: Box<dyn Backend>,
    note: Option<String>,
    luts: Option<Vec<BrdfLut>>,
    warnings: Vec<String>,
}

impl std::fmt::Debug for Baker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Baker")
            .field("opts", &self.opts)
            .field("backend", &self.backend.description())
            .finish()
    }
}

impl Baker {
    /// Checks every option (an [`Error::InvalidOption`] names the field) and opens the
    /// backend `opts.backend` names.
    pub fn new(opts: BakeOptions) -> Result<Baker> {
        opts.validate()?;
        let (backend, note) = create_backend(opts.backend)?;
        Ok(Baker {
            opts,
            backend,
            note,
            luts: None,
            warnings: Vec::new(),
        })
    }

    /// The options.
    pub fn options(&self) -> &BakeOptions {
        &self.opts
    }

    /// Bakes from now on with the sun `sun` (valid with every other option), on the same
    /// backend.
    pub fn set_sun(&mut self, sun: SunMode) {
        self.opts.sun = sun;
    }

    /// What the backend is, in words ("cpu (rayon, 2 threads)", "gpu: … (Vulkan)"): what
    /// runs where for `job`.
    pub fn backend_description(&self, job: BackendJob) -> String {
        self.backend.description_for(job)
    }

    /// Why [`BackendChoice::Auto`] chose the CPU backend, when it did for want of an adapter.
    pub fn backend_note(&self) -> Option<&str> {
        self.note.as_deref()
    }

    /// Warnings raised since the last call outside a bake (a GPU failure redone on the
    /// CPU); a bake's own are in its [`BakeReport::warnings`].
    pub fn take_warnings(&mut self) -> Vec<String> {
        std::mem::take(&mut self.warnings)
    }

    /// Whether a GPU failure of `result` is redone on the CPU: with
    /// [`BackendChoice::Auto`] it switches this and every later job to the CPU backend
    /// and records a warning.
    fn falls_back<T>(&mut self, result: &Result<T>) -> bool {
        match result {
            Err(e @ Error::Gpu { .. }) if self.opts.backend == BackendChoice::Auto => {
                self.warnings
                    .push(format!("{e}; continuing on the CPU backend"));
                self.backend = Box::new(CpuBackend);
                // Tables computed on the GPU are recomputed, so every output is the CPU's.
                self.luts = None;
                true
            }
            _ => false,
        }
    }

    /// Runs `f`, again on the CPU backend when the GPU fails (see [`Baker::falls_back`]).
    fn with_fallback<T>(&mut self, mut f: impl FnMut(&mut Self) -> Result<T>) -> Result<T> {
        let result = f(self);
        if self.falls_back(&result) {
            return f(self);
        }
        result
    }

    /// [`Baker::with_fallback`] for a job that consumes `env`: a copy is kept for the retry
    /// while the GPU may fail.
    fn with_env_fallback<T>(
        &mut self,
        env: Environment,
        f: impl Fn(&dyn Backend, Environment) -> Result<T>,
    ) -> Result<T> {
        let keep = (self.opts.backend == BackendChoice::Auto).then(|| env.clone());
        let result = f(self.backend.as_ref(), env);
        match keep {
            Some(env) if self.falls_back(&result) => f(self.backend.as_ref(), env),
            _ => result,
        }
    }

    /// The tables of the target's LUT files (computed once), or none when LUTs are off.
    fn target_luts(&mut self) -> Result<Vec<BrdfLut>> {
        if !self.opts.luts {
            return Ok(Vec::new());
        }
        if self.luts.is_none() {
            let luts = self
                .opts
                .target
                .luts
                .iter()
                .map(|spec| {
                    self.backend
                        .brdf_lut_model(DEFAULT_LUT_SIZE, DEFAULT_LUT_SIZE, spec.model)
                })
                .collect::<Result<Vec<_>>>()?;
            self.luts = Some(luts);
        }
        Ok(self.luts.clone().unwrap_or_default())
    }

    /// Bakes `input` (an equirect, a cross, a KTX2/DDS/KTX cubemap or a face pattern such as
    /// `sky_{face}.hdr`) into `out_root/<stem>/`: the target's file set, its LUTs when
    /// asked for, the preview when asked for, and `manifest.json`.
    pub fn bake(&mut self, input: &Path, out_root: &Path) -> Result<BakeReport> {
        self.bake_with_progress(input, out_root, &mut |_| {})
    }

    /// [`Baker::bake`], calling `progress` as each [`Stage`] starts.
    pub fn bake_with_progress(
        &mut self,
        input: &Path,
        out_root: &Path,
        progress: &mut dyn FnMut(Stage),
    ) -> Result<BakeReport> {
        let mut report = self.with_fallback(|baker| {
            let luts = baker.target_luts()?;
            bake(
                baker.backend.as_ref(),
                input,
                out_root,
                &baker.opts,
                &luts,
                progress,
            )
        })?;
        let mut warnings = self.take_warnings();
        warnings.append(&mut report.warnings);
        report.warnings = warnings;
        Ok(report)
    }

    /// Reads an environment (an equirect, a cross, a KTX2/DDS/KTX cubemap, or a face
    /// pattern such as `sky_{face}.hdr`) with the options' exposure applied. With
    /// `cube_size`, an equirect is reduced as it is read to what a cube of that edge needs
    /// (a bake reads its input for the specular size); without, it is kept whole.
    pub fn load(&self, input: &Path, cube_size: Option<u32>) -> Result<LoadedInput> {
        load_input(input, &self.input_options(cube_size))
    }

    /// Reads six square face images in the order +X, −X, +Y, −Y, +Z, −Z (see
    /// [`Baker::load`]).
    pub fn load_faces(
        &self,
        faces: &[std::path::PathBuf],
        cube_size: Option<u32>,
    ) -> Result<LoadedInput> {
        load_faces(faces, &self.input_options(cube_size))
    }

    fn input_options(&self, cube_size: Option<u32>) -> InputOptions {
        InputOptions {
            cube_size,
            ..self.opts.input_options()
        }
    }

    /// Bakes `env` in memory, in the generic orientation (for callers that write their own
    /// files): the specular chain, the irradiance cube, the SH when asked for, and the
    /// sheen chain when the target has one.
    pub fn bake_environment(&mut self, env: Environment) -> Result<BakedEnvironment> {
        self.bake_environment_with_progress(env, &mut |_| {})
    }

    /// [`Baker::bake_environment`], calling `progress` as each [`Stage`] starts.
    pub fn bake_environment_with_progress(
        &mut self,
        env: Environment,
        progress: &mut dyn FnMut(Stage),
    ) -> Result<BakedEnvironment> {
        let opts = self.opts.clone();
        let progress = std::cell::RefCell::new(progress);
        self.with_env_fallback(env, |backend, env| {
            let mut progress = progress.borrow_mut();
            bake_environment(backend, env, &opts, &mut **progress, &mut Vec::new())
        })
    }

    /// The BRDF LUT of `model`, `size`² texels.
    pub fn lut(&mut self, model: LutModel, size: u32) -> Result<BrdfLut> {
        self.with_fallback(|baker| baker.backend.brdf_lut_model(size, size, model))
    }

    /// The `size`² LTC table that goes with the LUT `model` (`plan::ltc::ltc_brdf` says
    /// which BRDF it fits).
    pub fn ltc(&mut self, model: LutModel, size: u32) -> Result<LtcTable> {
        let brdf = ltc_brdf(model, size)?;
        self.with_fallback(|baker| baker.backend.fit_ltc(brdf, size))
    }

    /// The LTC table the preview and the viewer shade area lights of `brdf` from, fitted on
    /// this baker's backend once a process (`backend::shared_ltc_table`).
    pub fn shared_ltc_table(&mut self, brdf: LightBrdf) -> Result<Arc<LtcTable>> {
        self.with_fallback(|baker| shared_ltc_table(baker.backend.as_ref(), brdf))
    }

    /// `env` as a cube of edge `size` (default: the largest power of two ≤ an equirect's
    /// width / 4, or a cube's own edge) with the full mip chain when `mips` is set,
    /// rotated by the options' rotation and stored in the target's orientation.
    pub fn cubemap(&mut self, env: Environment, size: Option<u32>, mips: bool) -> Result<Cubemap> {
        let size = size.unwrap_or_else(|| default_cube_size(&env));
        crate::stages::convert::validate_cube_size("size", size)?;
        let rotate = self.opts.rotate_degrees;
        let target = self.opts.target;
        // By value: the input's finest level becomes the pyramid's without a copy.
        let cube = self.with_env_fallback(env, |backend, env| {
            environment_into_cube(backend, env, size, mips, rotate)
        })?;
        Ok(target.orientation.apply(cube))
    }

    /// Writes `cube` (as [`Baker::cubemap`] returns it) to `path` in the container its
    /// extension names, a block format (BC6H) encoded on this baker's backend; refuses a
    /// pixel format the target's engine cannot read, and warns (see
    /// [`Baker::take_warnings`]) about values the format clips. Returns the paths written.
    pub fn write_cubemap(
        &mut self,
        path: &Path,
        cube: &Cubemap,
        opts: &CubeWriteOptions,
    ) -> Result<Vec<std::path::PathBuf>> {
        self.opts.target.check_format(opts.format)?;
        if Container::of_path(path).is_some_and(Container::is_texture) {
            self.warnings.extend(clip_warning(cube, opts.format));
        }
        self.with_fallback(|baker| write_cubemap_with(path, cube, opts, baker.backend.as_ref()))
    }

    /// The preview of `baked` (generic orientation; `name` in its caption) with `lut` (the
    /// table of the shading's LUT where the caller has it; computed when `None` or another
    /// table, `stages::preview::shading_lut`).
    pub fn preview(
        &mut self,
        name: &str,
        baked: &BakedEnvironment,
        lut: Option<&BrdfLut>,
        opts: &PreviewOptions,
    ) -> Result<Preview> {
        self.with_fallback(|baker| preview_baked(baker.backend.as_ref(), name, baked, lut, opts))
    }
}
