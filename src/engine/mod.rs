//! The engine: runs the scenes of a spec (`scene`), checks its limits (`check`, comparing a value
//! with a limit in `limit`) and golden curves (`golden`), optimises the modification
//! (`optimise`) and runs the accuracy ladder (`accuracy`), summarises the headline results of
//! each scene (`summary`), and computes what the design review draws of the disc (`drawing`) and of its solid
//! (`commands::solid_picture`, beside the export it draws);
//! the torsion curve under a locked input and its catalogue figures (`torsion`); the crank
//! bearing's rating life (`bearing_life`); the pins' stresses, the contact fatigue lives and the
//! bearing's static safety (`strength`); the plausibility bands of the headlines
//! (`plausibility`). It returns data: the tables, sentences and notes
//! made of it are built in `report` (the engine's own words are its errors, the `at` labels of
//! checks, names, and the files it writes).

pub mod accuracy;
pub mod as_built;
pub mod bearing_life;
pub mod commands;
pub mod design_search;
pub mod drawing;
pub mod duty_cycle;
pub mod duty_fatigue;
pub mod efficiency;
pub mod face_profile;
pub mod golden;
pub mod limit;
pub mod mass_properties;
pub mod missing;
pub mod optimise;
pub mod plausibility;
pub mod resolution;
pub mod scene;
pub mod shard_file;
pub mod strength;
pub mod summary;
pub mod tolerance;
pub mod torque_curve;
pub mod torsion;
pub mod verdict;
