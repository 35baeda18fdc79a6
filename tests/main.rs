//! Integration tests across `poly`, `groebner` and `render`: one test binary, one `mod` per
//! topic, to keep link time down (STYLE.md §7).
