"""What hexaleg shows: matplotlib figures, the report, and the meshcat viewer."""
