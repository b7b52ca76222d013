//! Generated meshes (placeholder until the generator lands).
