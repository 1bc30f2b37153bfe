//! The LTC table the preview and the viewer shade area lights from ([`shared_ltc_table`]):
//! [`SHARED_TABLE_SIZE`]² cells of the light BRDF, fitted once a process by each backend
//! that asks (`plan::ltc` says what a cell holds; `Backend::fit_ltc` where it runs), so that
//! every render of a process on one backend, and the viewer's two renderers, which share
//! the table of the light they show, read the same numbers.

use std::sync::{Arc, Mutex};

use super::{Backend, BackendJob};
use crate::plan::ltc::LtcTable;
use crate::plan::shading::LightBrdf;
use crate::Result;

/// Cells per side of the table the preview and the viewer shade area lights from: the
/// mean of `tests/ltc.rs`'s lights within 1.5 % of brute force at r = 0.25 (2.8 % at
/// 16²), a fit of 13 CPU-s on the CPU backend and 2.9 on lavapipe (docs/accuracy.md, "The
/// LTC fit on either backend").
pub const SHARED_TABLE_SIZE: u32 = 32;

/// The tables fitted in this process: by BRDF and where the fit ran.
type Fitted = Vec<(LightBrdf, String, Arc<LtcTable>)>;
static SHARED: Mutex<Fitted> = Mutex::new(Vec::new());

/// The [`SHARED_TABLE_SIZE`]² table of `brdf`, fitted by `backend` once a process (the
/// kernels of two backends that fit on the same device share one table). The two fits
/// agree within 0.02 % of a light's shading at r ≥ 0.1; below it they part (docs/accuracy.md).
pub fn shared_ltc_table(backend: &dyn Backend, brdf: LightBrdf) -> Result<Arc<LtcTable>> {
    let fitter = backend.description_for(BackendJob::LtcFit);
    let mut tables = SHARED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, _, t)) = tables.iter().find(|(b, f, _)| *b == brdf && *f == fitter) {
        return Ok(Arc::clone(t));
    }
    let table = Arc::new(backend.fit_ltc(brdf, SHARED_TABLE_SIZE)?);
    tables.push((brdf, fitter, Arc::clone(&table)));
    Ok(table)
}
