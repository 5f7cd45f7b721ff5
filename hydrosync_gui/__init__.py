"""HydroSync Qt shell: main window, project browser, plugin host, workers."""
