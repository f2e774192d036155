//! Arithmetic primitives of the datapath, one per file. Every block
//! registers its output and holds while `advance` is low.

pub mod adder;
pub mod certificate;
pub mod compare;
pub mod convert;
pub mod cross_product;
pub mod delay_line;
pub mod dot_product;
pub mod multiplier;
pub mod one_hot_choice;
pub mod register_copy;
pub mod sign;
pub mod subtractor;
#[cfg(test)]
pub(crate) mod unit_vectors;
pub mod valid_line;
