// placeholder: implemented by the hal work
