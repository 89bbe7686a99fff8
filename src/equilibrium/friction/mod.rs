//! Friction at the contacts of the disc (MODEL.md "Friction, efficiency and heat"): the
//! rigid-body sliding speeds at the nominal ratio (`sliding`), on which the losses and the
//! coupled balance are built.

pub mod loss;
pub mod sliding;
