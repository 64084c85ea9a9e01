"""The legs' own structure: internal wrenches, tube stresses, foot deflection, sizing."""
