//! Shared code of the integration tests: the independent f64 references ([`reference`])
//! and the fixtures ([`fixtures`]).
// Each test crate uses a part of them.
#![allow(dead_code, unused_imports)]

pub mod fixtures;
pub mod reference;

pub use fixtures::*;
pub use reference::*;
