//! A small SVG plotting kit for the design-review report, written with maud (text escaped by
//! construction): nice tick values (`ticks`), the frame every plot shares and the mapping of
//! drawings in mm to pixels (`frame`), line plots (`line`), and maps over a grid with a colour
//! bar (`map`: objective maps, roller × crank heat maps), label placement clear of the drawing
//! (`labels`), on what they all share (`base`:
//! colours, pixels, the document). Plain SVG 1.1 text, no JavaScript.

pub mod base;
pub mod frame;
pub mod labels;
pub mod line;
pub mod map;
pub mod ticks;

pub use frame::Frame;
pub use line::{axis_label, LinePlot, Mark, RefLine, Series, YCut};
pub use map::{MapCell, MapPlot, Marker, Shape, LOG_SPAN};
pub use ticks::{ticks, Ticks};

pub use base::{document, points, px, text_width, trimmed, widest, FONT, PALETTE, RED};
