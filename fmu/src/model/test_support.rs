//! What the instance's unit tests share: an instance whose log is recorded, and shortcuts.

use std::cell::RefCell;
use std::rc::Rc;

use super::{Instance, InstantiateArguments, Slave};
use crate::logging::{LogSink, Status};
use crate::model_description::GUID;

pub(super) type Log = Rc<RefCell<Vec<(Status, String, String)>>>;

pub(super) struct Recorder(pub(super) Log);

impl LogSink for Recorder {
    fn log(&mut self, status: Status, category: &str, message: &str) {
        self.0.borrow_mut().push((status, category.to_owned(), message.to_owned()));
    }
}

pub(super) fn arguments(guid: &str) -> InstantiateArguments<'_> {
    InstantiateArguments {
        instance_name: "wheel 1",
        interface: Ok(crate::mode::Interface::CoSimulation),
        guid,
        resource_location: Some("file:///tmp/resources/"),
        logging_on: false,
    }
}

pub(super) fn new_instance() -> (Instance, Log) {
    let log = Log::default();
    (instance_logging_to(&log), log)
}

/// A new instance whose messages go to `log`.
pub(super) fn instance_logging_to(log: &Log) -> Instance {
    Instance::instantiate(arguments(GUID), Box::new(Recorder(log.clone()))).unwrap()
}

pub(super) fn last_message(log: &Log) -> String {
    log.borrow().last().map(|(_, _, m)| m.clone()).unwrap_or_default()
}

/// Instantiated → initialization mode → step mode, with the start values.
pub(super) fn stepping() -> (Instance, Log) {
    let log = Log::default();
    (stepping_logging_to(&log), log)
}

/// [`stepping`], its messages going to `log`.
pub(super) fn stepping_logging_to(log: &Log) -> Instance {
    let mut instance = instance_logging_to(log);
    assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
    assert_eq!(instance.enter_initialization_mode(), Status::Ok);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    instance
}

pub(super) fn get(instance: &mut Instance, value_reference: u32) -> f64 {
    let mut value = [f64::NAN];
    assert_eq!(instance.get_real(&[value_reference], &mut value), Status::Ok, "{value_reference}");
    value[0]
}

/// `stiffness_source = measured_curve`.
pub(super) const MEASURED_CURVE: i32 = crate::model_description::StiffnessSource::MeasuredCurve as i32;

/// A point where every input matters: combined creepage with spin, partly saturated.
pub(super) fn at_a_general_point() -> (Instance, Log) {
    let (mut instance, log) = stepping();
    instance.set_real(
        &[
            crate::model_description::value_reference::CREEPAGE_LATERAL,
            crate::model_description::value_reference::SPIN_CREEPAGE,
        ],
        &[-0.6e-3, 0.3],
    );
    assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
    (instance, log)
}
