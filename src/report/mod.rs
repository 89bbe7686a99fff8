//! Outputs: the terminal table, the results JSON, JUnit XML and the HTML design review.

pub mod accuracy;
pub mod as_built;
pub mod disc;
pub mod explain;
pub mod export;
pub mod fit;
pub mod golden;
pub mod html;
pub mod json;
pub mod junit;
pub mod optimisation;
pub mod plots;
pub mod svg;
pub mod table;
pub mod terminal;
pub mod tolerance;
pub mod tolerance_review;
pub mod torsion;
