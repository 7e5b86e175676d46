//! What the master needs from `modelDescription.xml`: the GUID, the model identifier, and the
//! variables by name (value reference, causality, enumeration items).

use std::collections::BTreeMap;

/// One scalar variable.
#[derive(Debug, Clone)]
pub struct Variable {
    pub name: String,
    pub value_reference: u32,
    pub causality: String,
    /// `Real`, `Integer`, `Enumeration`, `Boolean` or `String`.
    pub type_name: String,
    /// For an enumeration: its items (name, value) in declaration order.
    pub items: Vec<(String, i32)>,
}

/// The parts of a model description the master uses.
#[derive(Debug, Clone)]
pub struct Description {
    pub guid: String,
    pub model_identifier: String,
    pub variables: Vec<Variable>,
}

impl Description {
    pub fn parse(xml: &str) -> Result<Description, String> {
        let document = roxmltree::Document::parse(xml).map_err(|e| format!("modelDescription.xml: {e}"))?;
        let root = document.root_element();
        let guid = root.attribute("guid").ok_or("no guid")?.to_owned();
        let model_identifier = root
            .children()
            .find(|node| node.has_tag_name("CoSimulation"))
            .and_then(|node| node.attribute("modelIdentifier"))
            .ok_or("no CoSimulation modelIdentifier")?
            .to_owned();
        let mut enumerations: BTreeMap<&str, Vec<(String, i32)>> = BTreeMap::new();
        for simple_type in root.descendants().filter(|node| node.has_tag_name("SimpleType")) {
            let items = simple_type
                .descendants()
                .filter(|node| node.has_tag_name("Item"))
                .map(|item| {
                    let value = item.attribute("value").and_then(|v| v.parse().ok()).ok_or("Item without value")?;
                    Ok((item.attribute("name").ok_or("Item without name")?.to_owned(), value))
                })
                .collect::<Result<Vec<_>, &str>>()?;
            enumerations.insert(simple_type.attribute("name").ok_or("SimpleType without name")?, items);
        }
        let variables = root
            .descendants()
            .filter(|node| node.has_tag_name("ScalarVariable"))
            .map(|node| {
                let name = node.attribute("name").ok_or("ScalarVariable without name")?.to_owned();
                let value_reference =
                    node.attribute("valueReference").and_then(|v| v.parse().ok()).ok_or("no valueReference")?;
                let type_node =
                    node.children().find(|child| child.is_element()).ok_or("ScalarVariable without type")?;
                let items = type_node
                    .attribute("declaredType")
                    .and_then(|declared| enumerations.get(declared))
                    .cloned()
                    .unwrap_or_default();
                Ok(Variable {
                    name,
                    value_reference,
                    causality: node.attribute("causality").unwrap_or("local").to_owned(),
                    type_name: type_node.tag_name().name().to_owned(),
                    items,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(Description { guid, model_identifier, variables })
    }

    pub fn variable(&self, name: &str) -> Result<&Variable, String> {
        self.variables.iter().find(|v| v.name == name).ok_or_else(|| format!("no variable named {name}"))
    }

    pub fn value_reference(&self, name: &str) -> Result<u32, String> {
        Ok(self.variable(name)?.value_reference)
    }

    /// The value of the enumeration item `item` of variable `name`.
    pub fn item(&self, name: &str, item: &str) -> Result<i32, String> {
        let variable = self.variable(name)?;
        variable
            .items
            .iter()
            .find(|(n, _)| n == item)
            .map(|(_, v)| *v)
            .ok_or_else(|| format!("{name} has no item {item}"))
    }

    /// The Real outputs, in the order of the model description.
    pub fn real_outputs(&self) -> Vec<&Variable> {
        self.variables.iter().filter(|v| v.causality == "output" && v.type_name == "Real").collect()
    }
}
