//! One entry per command, each returning data: `check`, `optimise`, `accuracy`, `tolerance`
//! and `design` (whole, a shard, the merge), `fit`, `profile`, `bless`. The command line, the library's
//! users and the tests call these; what they print or write is built in `report`.

mod accuracy;
mod bless;
mod check;
mod design;
mod fit;
mod optimise;
mod profile;
pub mod solid_picture;
mod spec_text;
mod tolerance;

pub use accuracy::accuracy;
pub use bless::bless;
pub use check::{
    check, map_steps_allowed, studies, AsBuilt, CheckOptions, CheckRun, Review, ReviewOptions,
    MAX_MAP_STEPS,
};
pub use design::{
    design, design_file, design_from_shards, design_name, design_shard, front_checks, front_spec,
    merge_design_shards, DesignRun, MergedDesign,
};
pub use fit::fit;
pub use optimise::{optimise, OptimiseRun};
pub use profile::{crowned, disc, profile, Disc, DiscSource, MIN_PROFILE_TOLERANCE_MM};
pub use tolerance::{
    failure_rate_check, merge_shards, tolerance, tolerance_shard, Merged, ToleranceRun,
};
