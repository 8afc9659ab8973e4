//! # Checker (`type = "checker"`)
//!
//! Unit squares of the scaled coordinates `st` alternate between two textures: square `(i, j)` (with
//! `i = ⌊s⌋`, `j = ⌊t⌋`) shows `a` when `i + j` is even — so the square `[0, 1)²` is `a` — and `b`
//! otherwise. `a` and `b` are textures themselves (usually colours).
//!
//! | parameter  | type              | default    | meaning                                  |
//! |------------|-------------------|------------|------------------------------------------|
//! | `a`, `b`   | colour or texture | 0.8, 0.2   | the two squares                          |
//! | `uv_scale` | `[su, sv]`        | `[10, 10]` | squares per unit of `u` and of `v`       |
//!
//! ```toml
//! [objects.material]
//! type = "diffuse"
//! reflectance = { type = "checker", a = [0.9, 0.9, 0.9], b = [0.1, 0.1, 0.1], uv_scale = [8, 8] }
//! ```

/// True when `st` falls in a square of the first texture (`⌊s⌋ + ⌊t⌋` even).
pub fn is_first(st: [f64; 2]) -> bool {
    // `floor` of a non-finite coordinate casts to 0 or saturates: no panic, some square.
    let i = st[0].floor() as i64;
    let j = st[1].floor() as i64;
    i.wrapping_add(j).rem_euclid(2) == 0
}
