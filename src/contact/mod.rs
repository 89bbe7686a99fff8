//! Contact between the disc and a roller or output pin: force–approach laws and Hertz
//! line-contact pressure.

pub mod face_width;
pub mod fatigue;
pub mod hertz_line;
pub mod law;
