//! fmi2Get/Set of values: every value reference checked first (all or nothing), the variable's
//! type and causality, fixed parameters only before initialisation ends; in initialization mode
//! a read of an output first brings the outputs up to date.

use std::ffi::CString;

use super::Instance;
use crate::logging::Status;
use crate::mode::{Call, Mode};
use crate::model_description::{access, access_of, variable, Causality, Kind};
use wheel_rail_contact::scene::Evaluation;

/// The FMI base types of the Get/Set functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueType {
    Real,
    Integer,
    Boolean,
    String,
}

impl ValueType {
    fn of(kind: &Kind) -> ValueType {
        match kind {
            Kind::Real { .. } => ValueType::Real,
            Kind::Integer { .. } | Kind::Enumeration { .. } => ValueType::Integer,
            Kind::String { .. } => ValueType::String,
        }
    }

    /// The [`ACCESS`](crate::model_description::ACCESS) bit of the type (none for Boolean:
    /// this FMU has no such variables).
    #[inline]
    fn access_bit(self) -> u8 {
        match self {
            ValueType::Real => access::REAL,
            ValueType::Integer => access::INTEGER,
            ValueType::String => access::STRING,
            ValueType::Boolean => 0,
        }
    }

    fn name(self) -> &'static str {
        match self {
            ValueType::Real => "Real",
            ValueType::Integer => "Integer",
            ValueType::Boolean => "Boolean",
            ValueType::String => "String",
        }
    }
}

impl Instance {
    /// Whether a variable of these [`ACCESS`](crate::model_description::ACCESS) bits can be
    /// written as `value_type` now.
    #[inline]
    fn settable(&self, bits: u8, value_type: ValueType) -> bool {
        bits & value_type.access_bit() != 0
            && (bits & access::WRITABLE != 0 || (bits & access::FIXED != 0 && self.run.mode != Mode::StepComplete))
    }

    /// Why `value_reference` cannot be written as `value_type` now (only called when it cannot).
    #[cold]
    fn not_settable(&self, value_reference: u32, value_type: ValueType) -> String {
        match variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) if ValueType::of(&v.kind) != value_type => {
                format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name())
            }
            Some(v) if v.causality == Causality::Output => format!("{} is an output and cannot be set", v.name),
            Some(v) => format!("{} is a fixed parameter and cannot be set after initialization", v.name),
        }
    }

    #[inline]
    fn readable(value_reference: u32, value_type: ValueType) -> bool {
        access_of(value_reference) & value_type.access_bit() != 0
    }

    #[cold]
    fn not_readable(value_reference: u32, value_type: ValueType) -> String {
        match variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) => format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name()),
        }
    }

    /// Checks every reference first, so that a call sets either all its values or none; when
    /// one is a parameter, the scene built from the parameters is forgotten. One pass over one
    /// byte of the generated access table per reference.
    #[inline]
    fn prepare_set(&mut self, call: Call, value_references: &[u32], value_type: ValueType) -> Result<(), Status> {
        self.require(call)?;
        let mut written = 0;
        for &value_reference in value_references {
            let bits = access_of(value_reference);
            if !self.settable(bits, value_type) {
                let reason = self.not_settable(value_reference, value_type);
                return Err(self.log.fail(call, &reason));
            }
            written |= bits;
        }
        if written & access::PARAMETER != 0 {
            self.model.parameters_changed();
        }
        Ok(())
    }

    /// Checks the references and, in initialization mode, brings the outputs up to date with
    /// the values just set if any is read: the status of the call (fmi2Warning for outputs of an
    /// exact solve that stopped at its limits), or the error.
    #[inline]
    fn prepare_get(&mut self, call: Call, value_references: &[u32], value_type: ValueType) -> Result<Status, Status> {
        self.require(call)?;
        if let Some(&value_reference) = value_references.iter().find(|&&r| !Self::readable(r, value_type)) {
            let reason = Self::not_readable(value_reference, value_type);
            return Err(self.log.fail(call, &reason));
        }
        let reads_output = || value_references.iter().any(|&r| access_of(r) & access::OUTPUT != 0);
        if self.run.mode == Mode::InitializationMode && reads_output() {
            return self.update_outputs(call, Evaluation::Initialise);
        }
        Ok(Status::Ok)
    }

    #[inline]
    pub fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetReal, value_references, ValueType::Real) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.values.real_mut(value_reference) {
                *field = value;
            }
        }
        self.log.trace(|| format!("fmi2SetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    #[inline]
    pub fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status {
        let status = match self.prepare_get(Call::GetReal, value_references, ValueType::Real) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = self.run.values.real(value_reference).unwrap_or(f64::NAN);
        }
        self.log.trace(|| format!("fmi2GetReal: {value_references:?} = {values:?}"));
        status
    }

    /// fmi2SetInteger: Integer and Enumeration variables.
    pub fn set_integer(&mut self, value_references: &[u32], values: &[i32]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetInteger, value_references, ValueType::Integer) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.values.integer_mut(value_reference) {
                *field = value;
            }
        }
        self.log.trace(|| format!("fmi2SetInteger: {value_references:?} = {values:?}"));
        Status::Ok
    }

    pub fn get_integer(&mut self, value_references: &[u32], values: &mut [i32]) -> Status {
        let status = match self.prepare_get(Call::GetInteger, value_references, ValueType::Integer) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = self.run.values.integer(value_reference).unwrap_or_default();
        }
        self.log.trace(|| format!("fmi2GetInteger: {value_references:?} = {values:?}"));
        status
    }

    /// fmi2SetString: copies of the texts (the caller's pointers are not kept); a String is a
    /// parameter, so the contact is rebuilt (the profiles read again) at the next evaluation.
    pub fn set_string<T: AsRef<str>>(&mut self, value_references: &[u32], values: &[T]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetString, value_references, ValueType::String) {
            return status;
        }
        for (&value_reference, value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.strings.string_mut(value_reference) {
                value.as_ref().clone_into(field);
            }
        }
        self.log.trace(|| {
            let texts: Vec<&str> = values.iter().map(AsRef::as_ref).collect();
            format!("fmi2SetString: {value_references:?} = {texts:?}")
        });
        Status::Ok
    }

    /// fmi2GetString: the values as C strings, kept by the instance until its next fmi2GetString
    /// (FMI 2.0 §2.1.7: valid until the next call on the instance, and longer).
    pub fn get_string(&mut self, value_references: &[u32]) -> Result<&[CString], Status> {
        match self.prepare_get(Call::GetString, value_references, ValueType::String) {
            Ok(_) => {}
            Err(status) => return Err(status),
        }
        let texts: Vec<CString> = value_references
            .iter()
            .map(|&r| {
                let text = self.run.strings.string(r).map_or("", String::as_str);
                // A NUL cannot come through fmi2SetString (it ends a C string).
                CString::new(text).unwrap_or_default()
            })
            .collect();
        self.log.trace(|| format!("fmi2GetString: {value_references:?} = {texts:?}"));
        self.returned_strings = texts;
        Ok(&self.returned_strings)
    }

    /// fmi2GetBoolean: this FMU has no such variables, so only n = 0 succeeds.
    pub fn get_absent_type(&mut self, call: Call, value_type: ValueType, value_references: &[u32]) -> Status {
        match self.prepare_get(call, value_references, value_type) {
            Ok(status) | Err(status) => status,
        }
    }

    /// fmi2SetBoolean: this FMU has no such variables, so only n = 0 succeeds.
    pub fn set_absent_type(&mut self, call: Call, value_type: ValueType, value_references: &[u32]) -> Status {
        match self.prepare_set(call, value_references, value_type) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }
}
