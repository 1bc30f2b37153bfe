// Workgroup size of every kernel, set by the Rust side at pipeline creation
// (`gpu::compute::ComputeKernel`), so the dispatch arithmetic and the shader agree.
override WORKGROUP_X: u32;
override WORKGROUP_Y: u32;
override WORKGROUP_Z: u32;
