//! Mirrors `linkage_core`'s `synthesis/`: precision points (Burmester, Freudenstein) and path
//! synthesis (atlases, circuits, distances, curve equations).

pub mod path;
pub mod precision;
