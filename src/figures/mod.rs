//! Figures: the thick body's fields as files ([`body`]) and the paper's figures and tables of
//! sections 2 and 3 regenerated from built-in scenes ([`paper`], `capstan figure`).

pub mod body;
pub mod paper;
pub mod reports;
pub mod settings;
pub mod solid_body;
pub mod threshold_trend;
