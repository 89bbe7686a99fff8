//! Outputs, and every text the tool shows: the terminal table and summary, the results JSON,
//! JUnit XML, the profile export, the HTML design review (`review`), and the words of every
//! other output — the accuracy ladder's table (`accuracy`), `check --explain` and the notes of
//! the results (`explain`), what `bless` did (`golden`), the optimiser's outcome
//! (`optimisation`), the tolerance study (`tolerance`), the disc as built (`as_built`, `fit`).
//! The engine returns data; this layer says it.

pub mod accuracy;
pub mod as_built;
pub mod check_review;
pub mod columns;
pub mod design;
pub mod explain;
pub mod export;
pub mod finite;
pub mod fit;
pub mod golden;
pub mod json;
pub mod json_text;
pub mod junit;
pub mod mass_properties;
pub mod optimisation;
pub mod place;
pub mod review;
pub mod step;
pub mod stl;
pub mod svg;
pub mod table;
pub mod terminal;
pub mod tolerance;
