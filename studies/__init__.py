"""Studies: cases -> runs -> JSON-line records -> tables and figures in reports/."""
