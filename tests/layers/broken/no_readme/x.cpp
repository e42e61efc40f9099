// A folder without a README.
