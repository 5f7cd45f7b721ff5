"""Importers: text formats of ``formats.md`` and real device logs."""
