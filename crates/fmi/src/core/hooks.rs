//! The hooks a declaration can carry ([`declare`](super::declare)): functions of the
//! model that the layer calls with an element index, never with a value reference.

/// Why `Model::output_derivative` gives no value.
#[derive(Debug, Clone, PartialEq)]
pub enum OutputDerivativeError {
    /// The model does not provide this derivative (this output, or this order of it):
    /// the importer asked for something the FMU does not offer (fmi2Error/fmi3Error).
    NotProvided(String),
    /// The model provides it but cannot evaluate it at this point (Discard).
    CannotEvaluate(String),
}

/// The `order`-th time derivative of output element i (0 for a scalar), at the
/// current time and state with the inputs held; the layer has checked the variable (a
/// Real output) and the order (1 ..= maxOutputDerivativeOrder), and the computed values
/// are current.
pub type OutputDerivative<M> = fn(&M, usize, u32) -> Result<f64, OutputDerivativeError>;
