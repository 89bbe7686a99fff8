//! Contact laws and Hertz line-contact pressure.
