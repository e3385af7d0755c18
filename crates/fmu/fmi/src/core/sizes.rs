//! The structural parameters' type and the sizes they hold (`core::structural` says
//! what the layer does with them): plain data and `fn` pointers, imported by the model
//! contract and the declarations without importing either.

/// At most this many structural parameters per model ([`Sizes`] holds them inline, so
/// a get or set allocates nothing).
pub const MAX_STRUCTURAL: usize = 4;

/// A structural parameter of model M (causality="structuralParameter",
/// variability="fixed": set in Configuration Mode, before initialization).
pub struct StructuralParameter<M: 'static> {
    pub name: &'static str,
    pub value_reference: u32,
    pub description: &'static str,
    /// The default size: the declared length of every array it sizes.
    pub start: usize,
    /// The largest size accepted (the smallest is 1).
    pub max: usize,
    /// The size the model holds now.
    pub get: fn(&M) -> usize,
    /// Changes the size the model holds (its vectors resized; the layer then writes
    /// the new elements' start values).
    pub resize: fn(&mut M, usize),
}

impl<M> Clone for StructuralParameter<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for StructuralParameter<M> {}

impl<M> StructuralParameter<M> {
    /// A structural parameter `name` at `value_reference`, default `start`, at most
    /// `max`, read with `get` and changed with `resize`.
    pub const fn new(
        name: &'static str,
        value_reference: u32,
        description: &'static str,
        [start, max]: [usize; 2],
        get: fn(&M) -> usize,
        resize: fn(&mut M, usize),
    ) -> Self {
        assert!(start >= 1 && start <= max, "a size is within 1..=max");
        StructuralParameter {
            name,
            value_reference,
            description,
            start,
            max,
            get,
            resize,
        }
    }

    /// The size `value` as set by an importer: within 1..=max, else why not.
    pub fn checked(&self, value: u64) -> Result<usize, String> {
        match usize::try_from(value) {
            Ok(n) if (1..=self.max).contains(&n) => Ok(n),
            _ => Err(format!(
                "\"{}\" = {value} is outside 1..={}: the value is kept at its previous size",
                self.name, self.max
            )),
        }
    }
}

/// The current value of each structural parameter of a model (inline: no allocation).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Sizes([usize; MAX_STRUCTURAL]);

impl Sizes {
    /// The sizes `model` holds now of its structural parameters `parameters`
    /// (`Model::STRUCTURAL`).
    pub fn of<M>(model: &M, parameters: &[StructuralParameter<M>]) -> Self {
        let mut n = [0; MAX_STRUCTURAL];
        for (slot, p) in n.iter_mut().zip(parameters) {
            *slot = (p.get)(model);
        }
        Sizes(n)
    }

    /// The value of structural parameter k.
    pub fn get(&self, k: usize) -> usize {
        self.0.get(k).copied().unwrap_or(0)
    }
}
