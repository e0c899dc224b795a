// placeholder: implemented by the ARCOS codec work
