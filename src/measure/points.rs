//! Reading measured points.
