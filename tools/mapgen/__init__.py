"""The FMPP map generator's parts: model (load, check, derive), sv, cpp, md."""
