"""Report of a reproduction run next to the thesis' Tables 4.1-4.3 (comparison tables, figures, REPORT.md)."""
